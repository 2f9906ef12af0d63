// A render session: the integrator its options choose, its pilots, its
// checkpoints and guiding field, and the render loop over its passes
// (integrator/run_passes.h), on a thread of its own or the caller's.
#include "lantern/render.h"

#include <tbb/global_control.h>

#include <chrono>
#include <condition_variable>
#include <exception>
#include <filesystem>
#include <mutex>
#include <new>
#include <optional>
#include <stdexcept>
#include <thread>

#include "accel/ray_dump.h"
#include "color/sensor.h"
#include "film/strategy_film.h"
#include "integrator/adaptive_sampling.h"
#include "integrator/bdpt.h"
#include "integrator/bdpt_wave.h"
#include "integrator/light_subpath_rate.h"
#include "integrator/merge_pilot.h"
#include "integrator/metropolis.h"
#include "integrator/pass_context.h"
#include "integrator/path_tracer.h"
#include "integrator/path_wave.h"
#include "integrator/render_checkpoints.h"
#include "integrator/render_progress.h"
#include "integrator/render_settings.h"
#include "integrator/run_passes.h"
#include "integrator/split_choice.h"
#include "lantern/error.h"
#include "trace/timeline.h"

namespace lantern {

namespace {

// The figures of a finished run that the film, the counters, the light
// sampler and the texture cache hold.
void finish_stats(const Scene& scene, const Film& film, const RayCounters& counters, const LightSampler& light_sampler,
                  RenderStats& st) {
  st.light_sampler = name(light_sampler.kind());
  st.light_sampler_seconds = light_sampler.build_seconds();
  st.light_sampler_bytes = light_sampler.memory_bytes();
  st.light_bvh_nodes = light_sampler.bvh().node_count();
  st.light_bvh_depth = light_sampler.bvh().depth();
  st.samples = film.total_samples();
  st.light_paths = film.light_paths();
  st.camera_rays = counters.camera;
  st.extension_rays = counters.extension;
  st.light_rays = counters.light;
  st.shadow_rays = counters.shadow;
  st.nonfinite_samples = film.nonfinite_samples();
  st.min_spp = film.min_samples_per_pixel();
  st.max_spp = film.max_samples_per_pixel();
  if (film.tracks_halves()) st.estimated_relmse = estimated_image_relmse(film);
  if (scene.textures.cache) {
    TextureCacheStats tc = scene.textures.cache->stats();
    st.texture_cache = true;
    st.texture_bytes_read = tc.bytes_read;
    st.texture_tiles_read = tc.tiles_read;
    st.texture_peak_tiles = tc.peak_tiles;
    st.texture_cache_bytes = tc.memory_bytes;
    st.texture_failed_lookups = tc.failed_lookups;
    st.texture_lookups = tc.lookups;
    st.texture_lookup_seconds = tc.lookup_seconds;
  }
}

}  // namespace

struct RenderSession::State {
  State(const Scene& s, RenderOptions o, RenderHooks h)
      : scene(s), opt(std::move(o)), hooks(std::move(h)), region(image_region(s, opt)), width(region.width),
        height(region.height), film(width, height, s.filter) {
    if (region.cropped()) film.set_region(region.x0, region.y0, region.full_width, region.full_height);
    const SensorSettings sensor{s.settings.iso, s.settings.exposure_time, s.settings.whitebalance,
                                ColorSpace::named(s.settings.color_space)};
    auto row_major = [](const Matrix3d& m) {
      std::array<float, 9> a;
      for (size_t i = 0; i < 9; ++i) a[i] = float(m[i / 3][i % 3]);
      return a;
    };
    film.set_sensor(row_major(sensor_matrix(sensor)));
    film.set_max_component(s.settings.max_component_value, row_major(sensor_rgb_matrix(sensor)));
  }
  const Scene& scene;
  const RenderOptions opt;
  const RenderHooks hooks;
  const ImageRegion region;  // the film's part of the camera's image
  const int width, height;
  Film film;
  mutable std::mutex film_mutex;
  std::atomic<bool> cancelled{false}, began{false}, ran{false};
  std::atomic<uint64_t> done{0};
  uint64_t total = 0;
  Clock::time_point start;
  std::thread thread;
  RenderResult result;
  std::exception_ptr error;
  std::mutex end_mutex;  // finished, for wait_for
  std::condition_variable end_cv;
  bool finished = false;
};

RenderSession::RenderSession(const Scene& scene, RenderOptions options, RenderHooks hooks) {
  check_options(scene, options);
  state_ = std::make_unique<State>(scene, std::move(options), std::move(hooks));
}

RenderSession::~RenderSession() {
  if (state_ && state_->thread.joinable()) {
    cancel();
    state_->thread.join();
  }
}

void RenderSession::cancel() { state_->cancelled.store(true); }
int RenderSession::width() const { return state_->width; }
int RenderSession::height() const { return state_->height; }

Image RenderSession::snapshot() const {
  std::lock_guard<std::mutex> lock(state_->film_mutex);
  return state_->film.resolve();
}

RenderProgress RenderSession::progress() const {
  const State& s = *state_;
  if (!s.began.load()) return RenderProgress{};
  return progress_at(s.opt, s.start, s.done.load(), s.total);
}

void RenderSession::start() {
  if (state_->ran.exchange(true)) throw std::logic_error("a render session runs once");
  state_->thread = std::thread([this] {
    try {
      state_->result = render_all();
    } catch (...) {
      state_->error = std::current_exception();
    }
    std::lock_guard<std::mutex> lock(state_->end_mutex);
    state_->finished = true;
    state_->end_cv.notify_all();
  });
}

bool RenderSession::wait_for(double seconds) {
  if (!state_->thread.joinable()) throw std::logic_error("wait_for() needs a started render session");
  std::unique_lock<std::mutex> lock(state_->end_mutex);
  return state_->end_cv.wait_for(lock, std::chrono::duration<double>(std::max(seconds, 0.0)),
                                 [&] { return state_->finished; });
}

RenderResult RenderSession::wait() {
  if (!state_->thread.joinable()) throw std::logic_error("wait() needs a started render session");
  state_->thread.join();
  if (state_->error) std::rethrow_exception(state_->error);
  return std::move(state_->result);
}

RenderResult RenderSession::run() {
  if (state_->ran.exchange(true)) throw std::logic_error("a render session runs once");
  return render_all();
}

RenderResult RenderSession::render_all() {
  State& s = *state_;
  const Scene& scene = s.scene;
  const RenderOptions& asked = s.opt;
  check_processes(asked, s.hooks);
  if (asked.gbuffer) s.film.track_moments();
  if (asked.spectral_buckets > 0 && s.film.buckets().count == 0)
    s.film.track_buckets({asked.spectral_buckets, asked.spectral_lambda_min, asked.spectral_lambda_max});
  // Low-discrepancy samplers lay a pixel's samples out for the count they
  // plan for; under a time budget the count is open.
  const uint32_t planned_spp = asked.time_limit_seconds > 0 ? 0u : uint32_t(asked.spp);
  std::optional<tbb::global_control> limit;
  if (asked.threads > 0) limit.emplace(tbb::global_control::max_allowed_parallelism, size_t(asked.threads));

  Film& film = s.film;
  const LightSampler light_sampler(scene.lights, scene.shapes, scene.textures, asked.light_sampler);
  // vcm whose merges do not pay renders as bdpt, in every respect
  // (merge_pilot.h); its pilots' time counts in a time budget.
  const Clock::time_point pilots_start = Clock::now();
  MergingChoice merging = choose_merging(scene, light_sampler, asked, s.region, planned_spp, bool(s.hooks.agree));
  agree_on(s.hooks, merging);
  const double merging_seconds = std::chrono::duration<double>(Clock::now() - pilots_start).count();
  const RenderOptions chosen = rendered_as(asked, merging, scene);
  const RenderOptions& opt = chosen;
  std::optional<StrategyFilm> strategy_film;
  if (opt.strategies) strategy_film.emplace(s.width, s.height, scene.filter);
  RayCounters counters;
  RenderResult res;
  std::unique_ptr<RayDump> dump;
  if (!opt.dump_rays.empty()) dump = std::make_unique<RayDump>(opt.dump_rays);
  CheckpointInfo info = [&] {
    std::lock_guard<std::mutex> lock(s.film_mutex);
    return start_checkpointing(opt, s.hooks, sequence_fingerprint(opt, s.region), film,
                               guiding_field_joiner(scene.bounds_lo, scene.bounds_hi, opt));
  }();
  res.resumed_samples = film.total_samples();
  const double prior_seconds = info.elapsed_seconds;
  s.start = Clock::now() - std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(merging_seconds));
  s.done = res.resumed_samples;
  s.total = uint64_t(s.width) * uint64_t(s.height) * (opt.time_limit_seconds > 0 ? 1 : uint64_t(opt.spp));
  s.began = true;
  Checkpointer checkpoints(opt, s.hooks, std::move(info), s.start);
  if (scene.textures.cache) scene.textures.cache->reset_lookup_stats(opt.collect_stats);
  StrategyFilm* strategies = strategy_film ? &*strategy_film : nullptr;
  std::optional<GuidingField> guiding;
  if (opt.any_guiding()) {
    guiding.emplace(new_guiding_field(scene.bounds_lo, scene.bounds_hi, opt));
    resume_guiding(*guiding, checkpoints, opt);
    checkpoints.learns([&guiding] { return guiding->save(); });
  }
  PassContext cx{scene, opt, s.hooks, counters, film, s.film_mutex, strategies, s.done, res.stats, dump.get(),
                 checkpoints, guiding ? &*guiding : nullptr, s.cancelled};
  bool interrupted = false;
  {
    ProgressReporter reporter(opt, s.hooks, s.start, s.done, s.total);
    bool stopped;
    auto run = [&cx](auto&& tracer) {
      tracer.set_guiding(cx.guiding);
      return run_passes(tracer, cx);
    };
    // The path tracer, its camera samples split in ps.split paths
    // (kSplitAuto: the pilot's choice). Guided, they stay whole while the
    // field learns, and the pilot runs once it has learnt, if passes of
    // more than one sample follow (pass_layout.h). Under MPI it runs before
    // the render instead, where the ranks agree on its choice: the ranks'
    // calls to agree must come before rank 0's scheduler thread, which
    // shares MPI with them, starts.
    auto run_path_tracer = [&](PathTracerSettings ps) {
      uint32_t unguided = split_once_unguided(scene, opt);  // a guided render's, once its field has learnt
      RenderStats pilot_stats;  // (its pilot's figures, reported if its camera samples split)
      if (cx.guiding) {
        if (unguided == kSplitAuto && s.hooks.agree) {
          PathTracerSettings pilot = ps;
          pilot.split = kSplitAuto;
          set_split(scene, light_sampler, opt, pilot, pilot_stats, s.hooks);
          unguided = pilot.split;
        }
      } else if (ps.split == kSplitAuto) {
        set_split(scene, light_sampler, opt, ps, res.stats, s.hooks);
      }
      res.stats.split = cx.split = ps.split;
      PathTracer tracer(scene, light_sampler, ps);
      if (cx.guiding && unguided != 1)
        cx.unguided_split = [&, ps, unguided]() mutable {
          ps.split = unguided;
          if (ps.split == kSplitAuto) {
            set_split(scene, light_sampler, opt, ps, res.stats, RenderHooks{});
          } else {
            res.stats.split_candidates = pilot_stats.split_candidates;
            res.stats.split_error = pilot_stats.split_error;
            res.stats.split_camera_share = pilot_stats.split_camera_share;
          }
          tracer.split_camera_samples(ps.split);
          return res.stats.split = ps.split;
        };
      const bool stopped = run(tracer);
      cx.unguided_split = nullptr;  // (it holds the tracer)
      return stopped;
    };
    if (opt.integrator == Integrator::Mlt) {
      stopped = run_metropolis(Bdpt(scene, light_sampler, bdpt_settings(scene, opt, s.region, planned_spp)),
                               metropolis_settings(scene, opt, s.region), cx);
    } else if (!traces_paths(opt.integrator)) {
      BdptSettings bs = bdpt_settings(scene, opt, s.region, planned_spp);
      res.stats.vcm_radius = bs.merging ? bs.vcm_radius : 0.f;
      if (bs.merging)
        res.stats.vcm_wave_paths = merging_wave_paths(uint32_t(film.width() * film.height()), opt.wave_size);
      PathTracerSettings eye_alone = path_settings(scene, opt, s.region, planned_spp);
      if (uses_light_subpath_rate(opt.integrator))
        set_light_subpath_rate(scene, light_sampler, opt, eye_alone, bs, res.stats, s.hooks,
                               merging.bdpt ? &*merging.bdpt : nullptr);
      report_merging(merging, merging_seconds, res.stats);
      // (no light subpaths: the path tracer, eye_subpaths_alone.h, whose
      // camera samples may split as its own do)
      if (bs.light_subpath_rate == 0.f) {
        stopped = run_path_tracer(eye_alone);
      } else {
        stopped = run(Bdpt(scene, light_sampler, bs));
      }
      if (bs.merging)  // the radius of the last pass traced (Bdpt::prepare_merging)
        res.stats.vcm_last_radius =
            bs.vcm_radius * std::pow(float(res.stats.vcm_last_first_sample + 1), 0.5f * (bs.vcm_alpha - 1.f));
    } else {
      stopped = run_path_tracer(path_settings(scene, opt, s.region, planned_spp));
    }
    // A stop that came after the last unit left nothing undone.
    interrupted = stopped && (cx.stop_requested() || cx.peer_interrupted);
  }
  const bool keep_piece = interrupted || opt.keep_checkpoint;
  if (checkpoints.enabled() && keep_piece) checkpoints.write(film);
  if (!opt.film_path.empty()) checkpoints.write_to(opt.film_path, film);
  if (s.hooks.reduce_film) {
    std::lock_guard<std::mutex> lock(s.film_mutex);
    s.hooks.reduce_film(film);
  }
  // Done: nothing left to resume. A rank's piece goes only once every
  // rank's film has joined (a rank out of units waits there while others
  // render, and one of them may yet die and leave the job to a resume).
  std::error_code ec;
  if (checkpoints.enabled() && !keep_piece) std::filesystem::remove(checkpoints.own_path(), ec);

  res.image = snapshot();
  if (opt.gbuffer) {
    // The visible surfaces of as many samples as the pixels took (lt takes
    // no camera samples: the budget's), up to 64: they converge long
    // before the image does.
    const uint32_t taken = film.min_samples_per_pixel() > 0 ? film.min_samples_per_pixel() : uint32_t(std::max(opt.spp, 1));
    const PathTracer tracer(scene, light_sampler, path_settings(scene, opt, s.region, planned_spp));
    add_gbuffer_channels(tracer.visible_surfaces(std::min(taken, 64u), opt.gbuffer_world, opt.ray_backend), film,
                         &res.image);
  }
  film.add_bucket_channels(&res.image);
  if (strategy_film) res.strategies = strategy_film->resolve(film);
  res.interrupted = interrupted;
  finish_stats(scene, film, counters, light_sampler, res.stats);
  if (opt.integrator == Integrator::Mlt) res.stats.samples = res.stats.mlt_traced;  // (the film counts no camera samples)
  if (guiding) guiding->report(res.stats);
  res.stats.seconds = std::chrono::duration<double>(Clock::now() - s.start).count();
  res.total_render_seconds = prior_seconds + res.stats.seconds;
  return res;
}

RenderResult render(const Scene& scene, const RenderOptions& options, const RenderHooks& hooks) {
  return RenderSession(scene, options, hooks).run();
}

}  // namespace lantern
