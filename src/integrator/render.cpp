// Splits the image into waves and runs them in parallel with oneTBB.
//
// Determinism: a pass covers a fixed range of sample indices for every
// pixel; within a pass each pixel belongs to exactly one wave, and a wave
// adds its samples in slot order. So every pixel sums its samples in sample
// index order whatever the thread count, and random numbers depend only on
// (seed, pixel, sample index, dimension).
#include <tbb/enumerable_thread_specific.h>
#include <tbb/global_control.h>
#include <tbb/parallel_for.h>

#include <chrono>
#include <condition_variable>
#include <mutex>
#include <optional>
#include <stdexcept>
#include <thread>

#include "integrator/path_tracer.h"
#include "integrator/path_wave.h"
#include "lantern/render.h"

namespace lantern {

namespace {

using Clock = std::chrono::steady_clock;

// Calls the progress callback twice a second from its own thread.
class ProgressReporter {
 public:
  ProgressReporter(const RenderOptions& o, Clock::time_point start, const std::atomic<uint64_t>& done, uint64_t total)
      : opts_(o), start_(start), done_(done), total_(total) {
    if (o.progress) thread_ = std::thread([this] { loop(); });
  }
  ~ProgressReporter() {
    {
      std::lock_guard<std::mutex> l(m_);
      stop_ = true;
    }
    cv_.notify_all();
    if (thread_.joinable()) thread_.join();
    if (opts_.progress) opts_.progress(snapshot());
  }

 private:
  RenderProgress snapshot() const {
    RenderProgress p;
    p.elapsed_seconds = std::chrono::duration<double>(Clock::now() - start_).count();
    p.samples_done = done_.load();
    p.fraction = opts_.time_limit_seconds > 0 ? std::min(1.0, p.elapsed_seconds / opts_.time_limit_seconds)
                                              : double(p.samples_done) / double(std::max<uint64_t>(total_, 1));
    return p;
  }
  void loop() {
    std::unique_lock<std::mutex> l(m_);
    while (!cv_.wait_for(l, std::chrono::milliseconds(500), [this] { return stop_; })) opts_.progress(snapshot());
  }
  const RenderOptions& opts_;
  Clock::time_point start_;
  const std::atomic<uint64_t>& done_;
  uint64_t total_;
  std::mutex m_;
  std::condition_variable cv_;
  bool stop_ = false;
  std::thread thread_;
};

}  // namespace

RenderResult render(const Scene& scene, const RenderOptions& opt) {
  if (opt.integrator != "path")
    throw std::invalid_argument("unknown integrator \"" + opt.integrator + "\"; available: path");
  if (opt.spp <= 0 && opt.time_limit_seconds <= 0) throw std::invalid_argument("--spp must be positive");
  if (opt.maxdepth < 0) throw std::invalid_argument("--maxdepth must be >= 0");
  if (opt.wave_size < 1 || opt.wave_size > (1 << 22)) throw std::invalid_argument("--wave-size must lie in [1, 4194304]");
  RayBackend backend = parse_ray_backend(opt.ray_backend);

  std::optional<tbb::global_control> limit;
  if (opt.threads > 0) limit.emplace(tbb::global_control::max_allowed_parallelism, size_t(opt.threads));

  PathTracerSettings ps;
  ps.maxdepth = opt.maxdepth;
  ps.seed = opt.seed;
  ps.width = opt.width > 0 ? opt.width : scene.settings.width;
  ps.height = opt.height > 0 ? opt.height : scene.settings.height;
  PathTracer tracer(scene, ps);
  Film film(ps.width, ps.height);
  std::vector<uint32_t> order = tile_order(ps.width, ps.height);

  const bool timed = opt.time_limit_seconds > 0;
  const uint32_t total_spp = timed ? 0xFFFFFFFFu : uint32_t(opt.spp);
  const uint32_t pass_spp = timed ? 1u : std::min<uint32_t>(total_spp, 16u);
  const uint32_t pixels_per_wave = std::max<uint32_t>(1, uint32_t(opt.wave_size) / pass_spp);
  const uint32_t capacity = pixels_per_wave * pass_spp;

  RayCounters counters;
  tbb::enumerable_thread_specific<std::unique_ptr<PathWave, void (*)(PathWave*)>> states(
      [&] { return tracer.make_wave_state(capacity, RayStream(scene.accel->handle(), backend, &counters)); });

  const auto start = Clock::now();
  std::atomic<uint64_t> done{0};
  std::atomic<bool> stop{false};
  bool interrupted = false;
  {
    ProgressReporter reporter(opt, start, done, uint64_t(order.size()) * (timed ? 1 : total_spp));
    const uint32_t waves = uint32_t((order.size() + pixels_per_wave - 1) / pixels_per_wave);
    for (uint32_t first = 0; first < total_spp && !stop; first += pass_spp) {
      uint32_t samples = std::min(pass_spp, total_spp - first);
      tbb::parallel_for(tbb::blocked_range<uint32_t>(0, waves, 1), [&](const tbb::blocked_range<uint32_t>& r) {
        for (uint32_t wi = r.begin(); wi != r.end(); ++wi) {
          if (stop.load(std::memory_order_relaxed)) return;
          if ((opt.cancel && opt.cancel->load()) ||
              (timed && std::chrono::duration<double>(Clock::now() - start).count() >= opt.time_limit_seconds)) {
            stop = true;
            return;
          }
          WaveDesc wave{order.data() + size_t(wi) * pixels_per_wave,
                        uint32_t(std::min<size_t>(pixels_per_wave, order.size() - size_t(wi) * pixels_per_wave)), first,
                        samples};
          tracer.trace(wave, *states.local(), film);
          done += wave.size();
        }
      });
    }
    interrupted = opt.cancel && opt.cancel->load();
  }

  RenderResult res;
  res.image = film.resolve();
  res.interrupted = interrupted;
  RenderStats& st = res.stats;
  st.seconds = std::chrono::duration<double>(Clock::now() - start).count();
  st.samples = film.total_samples();
  st.camera_rays = counters.camera;
  st.extension_rays = counters.extension;
  st.shadow_rays = counters.shadow;
  st.nonfinite_samples = film.nonfinite_samples();
  st.min_spp = film.min_samples_per_pixel();
  return res;
}

}  // namespace lantern
