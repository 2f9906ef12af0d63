// Splits the image into waves and runs them in parallel with oneTBB.
//
// Determinism: a pass covers a fixed range of sample indices for every
// pixel; waves record their samples and splats in slot order, and the film
// merges whole waves in wave order. So every sum is formed in the same order
// whatever the thread count, and random numbers depend only on (seed, pixel,
// sample index, dimension).
#include "lantern/render.h"

#include <tbb/enumerable_thread_specific.h>
#include <tbb/global_control.h>
#include <tbb/parallel_pipeline.h>
#include <tbb/task_arena.h>

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
#include "integrator/split_choice.h"
#include "integrator/ticket_cursor.h"
#include "integrator/wave_stats.h"
#include "lantern/error.h"
#include "trace/timeline.h"

namespace lantern {

namespace {

constexpr const char* kMergeQueue = "waves waiting for the film merge";

// Traces one wave; with a timeline, as a span on this thread's track with
// its stages and ray queries inside.
template <class Tracer, class State>
void trace_wave(const Tracer& tracer, const WaveDesc& wave, State& state, WaveOutput& out, Timeline* timeline,
                int64_t number) {
  TraceBuffer* track = timeline ? &timeline->local() : nullptr;
  state.stats.trace = track;
  state.stream.set_trace(track);
  if (!track) return tracer.trace(wave, state, out);
  track->begin_wave(number);
  {
    TraceSpan span(track, "wave", TraceCategory::Wave, int64_t(wave.size()));
    tracer.trace(wave, state, out);
  }
  track->counter(kMergeQueue, Clock::now(), ++timeline->merge_queue(), true);
  track->end_wave();
}

// A wave in the pipeline: its number in the pass, its output slot, and the
// pass (its first sample index).
struct WaveItem {
  uint32_t wave, slot, first;  // trivial: oneTBB carries it in place
};

// Adaptive sampling: the pixels of `wave` that take `pass`. Merging, every
// pixel's light subpath is still traced, so that each pass's merges and
// splats are what they are without adaptive sampling; the camera samples
// are taken, and the splats kept, only for the pixels that take the pass
// (WaveDesc::eye_pixels, WaveOutput::pass_light_paths).
void choose_adaptive(const AdaptivePasses& adaptive, uint32_t pass, bool merging, const Film& film,
                     uint64_t pass_light_paths, WaveDesc& wave, WaveOutput& out, std::vector<uint32_t>& active) {
  if (merging) {
    wave.eye_pixels = out.splat_pixels = pass >= 2 ? film.pass_mask(pass) : nullptr;
    out.pass_light_paths = pass_light_paths;
    return;
  }
  adaptive.choose(pass, wave.pixels, wave.pixel_count, active);
  wave.pixels = active.data();
  wave.pixel_count = uint32_t(active.size());
}

// Runs one integrator over all passes. Waves flow through a pipeline whose
// last stage adds their output to the film, one wave at a time (in wave
// order, though the fixed-point sums would not mind another).
template <class Tracer>
bool run_passes(const Tracer& tracer, PassContext& cx) {
  const RenderOptions& opt = cx.opt;
  const RenderHooks& hooks = cx.hooks;
  Film& film = cx.film;
  Checkpointer& checkpoints = cx.checkpoints;
  const RayBackend backend = opt.ray_backend;
  const std::vector<uint32_t> order = tile_order(film.width(), film.height());
  const bool timed = opt.time_limit_seconds > 0;  // the budget counts earlier runs too
  // Adaptive sampling to a budget: spp is the image's mean, each pixel's limit far above it.
  const AdaptiveGoal goal = adaptive_goal(opt, order.size());
  const bool budgeted = goal.on() && goal.target <= 0;
  const uint32_t total_spp = timed ? 0xFFFFFFFFu : budgeted ? kAdaptiveMaxSpp : uint32_t(opt.spp);
  // A pass is one sample per pixel for a timed render and for merging
  // (vcm, bpm, ppm): a pixel's samples then merge with the light vertices of
  // as many different waves, whatever the budget, and the merging radius
  // shrinks sample by sample. Otherwise up to 16, a pixel's samples
  // adjacent in its wave (coherent rays, fewer passes).
  // Guided paths too: the field learns in iterations of doubling length
  // from one sample per pixel (integrator/guiding_field.h). Not adaptive
  // sampling under a time limit, whose pixels differ in samples anyway: a
  // pass of one sample would be a wave or two, too few to keep the threads
  // busy (a timed adaptive render drew 30% fewer samples so). A timed
  // render whose camera samples are split takes one camera sample per
  // pixel a pass: its `split` paths.
  const bool merging = merges_vertices(opt.integrator);
  const uint32_t split = cx.split;
  const uint32_t pass_spp = merging || cx.guiding   ? 1u
                            : (timed && !goal.on()) ? split
                                                    : std::min<uint32_t>(total_spp, 16u);
  const uint32_t pixels_per_wave = merging ? merging_wave_paths(uint32_t(order.size()), opt.wave_size)
                                           : std::max<uint32_t>(1, uint32_t(opt.wave_size) / pass_spp);
  const uint32_t capacity = pixels_per_wave * pass_spp;
  const uint32_t waves = uint32_t((order.size() + pixels_per_wave - 1) / pixels_per_wave);
  checkpoints.set_units(timed ? 0 : (total_spp + pass_spp - 1) / pass_spp, waves);

  using State = typename decltype(tracer.make_wave_state(0, RayStream(nullptr, backend, nullptr)))::element_type;
  // Units: waves numbered through the whole render (passes one after
  // another). This run renders those of its share that the film lacks.
  auto unit_of = [&](uint32_t first, uint32_t wi) { return uint64_t(first / pass_spp) * waves + wi; };
  // The units done when this run began (of every process: the others'
  // too, for MPI's ranks that did not read the checkpoint): the serial
  // merge stage adds to this process's live set while the input stage, on
  // another thread, reads that separate one (units of this run are never
  // offered twice: the walk only moves on).
  const UnitShare share{opt.share_index, opt.share_count};
  UnitSet& merged = checkpoints.done();
  const UnitSet& done_before = checkpoints.done_before();
  auto wanted = [&](uint32_t first, uint32_t wi) {
    return share.holds(first / pass_spp, wi) && !done_before.contains(unit_of(first, wi));
  };
  tbb::enumerable_thread_specific<std::unique_ptr<State, void (*)(State*)>> states(
      [&] { return make_thread_state(tracer, capacity, cx); });
  double film_seconds = 0.0;
  // At most `tokens` waves are in flight and they retire in the order they
  // were issued, so the k-th wave issued can take slot k mod tokens: the
  // wave that had it has retired. (Not the wave's own number mod tokens:
  // with units skipped, for a share, a resume or tickets, two waves in
  // flight could have the same.)
  //
  // Adaptive sampling chooses the pixels of pass p at the end of pass p - 2
  // (adaptive_sampling.h): with no more waves in flight than a pass has,
  // the first wave of pass p - 1, whose merge takes that measurement, has
  // retired by the time pass p's first wave is issued. (A pass of adaptive
  // sampling may be two of the pipeline's: below.)
  //
  // Passes of one sample (merging, guiding) are decided in pairs, so that
  // every pixel's even and odd samples stay as many (Film::halves).
  // Merging, a pass's splats count only in the pixels that take it, scaled
  // by its own light paths (choose_adaptive): vcm's weights change from
  // pass to pass (the radius shrinks), so a pixel's light tracing must be
  // averaged over the passes its camera samples are.
  const uint32_t adaptive_spp = pass_spp == 1 ? 2 : pass_spp;
  AdaptivePasses adaptive(film, cx.film_mutex, order, pixels_per_wave, adaptive_spp, goal);
  size_t tokens = 2 * size_t(std::max(1, tbb::this_task_arena::max_concurrency()));
  if (adaptive.on()) tokens = std::min<size_t>(tokens, size_t(waves) * (adaptive_spp / pass_spp));
  std::vector<WaveOutput> outputs(tokens);
  for (WaveOutput& o : outputs) o.keep_spectra = film.buckets().count > 0;  // Film "spectral"
  std::vector<std::vector<uint32_t>> active(adaptive.on() ? tokens : 0);  // each slot's pixels that take the pass

  std::atomic<bool> stop{false};
  bool issued = false;  // a wave was started in this run
  uint64_t issued_items = 0;
  TicketCursor tickets(hooks.next_ticket);
  auto time_is_up = [&] { return timed && checkpoints.elapsed() >= opt.time_limit_seconds; };
  // One pipeline over all passes: the waves of the next pass start while
  // the last of this one are still in flight, so a pass of fewer waves
  // than threads (large vcm waves, small images) leaves no thread idle.
  uint32_t first = 0, next = 0;  // the input stage's pass and wave
  // The end of each pass, for hooks.pass_done: the samples per pixel reached.
  constexpr uint32_t kNoPass = 0xFFFFFFFFu;
  uint32_t merged_pass_first = kNoPass;
  auto pass_done = [&](uint32_t pass_first) {
    if (hooks.pass_done) hooks.pass_done(pass_first + std::min(pass_spp, total_spp - pass_first));
  };
  auto advance_pass = [&] {
    first += pass_spp;
    next = 0;
    return first < total_spp;
  };
  // While a guiding field learns, the pipeline stops at the end of each of
  // its iterations (the waves drain, the field is updated) and starts again.
  auto end_of_segment = [&]() -> uint64_t {
    return cx.guiding && cx.guiding->learning() ? cx.guiding->iteration_end() * pass_spp : UINT64_MAX;
  };
  for (uint64_t segment_end = end_of_segment();; segment_end = end_of_segment()) {
    tbb::parallel_pipeline(
        tokens,
        tbb::make_filter<void, WaveItem>(tbb::filter_mode::serial_in_order,
                                         [&](tbb::flow_control& fc) -> WaveItem {
                                           // A time budget shorter than the set-up still
                                           // renders one wave, so every run adds samples.
                                           // Without tickets the next unit is found before a
                                           // stop is looked at, so a stop after the last unit is
                                           // no interruption; with them, after, so that no
                                           // ticket is taken that will not be rendered.
                                           const bool ticketed = bool(hooks.next_ticket);
                                           for (;;) {
                                             if (first >= total_spp || first >= segment_end ||
                                                 adaptive.reached(first / adaptive_spp))
                                               break;
                                             if (!ticketed && !tickets.next(first, next, waves, wanted)) {
                                               if (advance_pass()) continue;
                                               break;  // the last pass is done
                                             }
                                             if (stop || cx.stop_requested() || (issued && time_is_up())) {
                                               stop = true;
                                               break;
                                             }
                                             if (ticketed && !tickets.next(first, next, waves, wanted)) {
                                               if (tickets.exhausted()) {
                                                 stop = true;
                                                 break;
                                               }
                                               if (advance_pass()) continue;  // this pass has no unit left for us
                                               break;
                                             }
                                             issued = true;
                                             // Slots by issue order: items retire in that order and
                                             // at most `tokens` are in flight, so a slot is free again
                                             // when it comes round (wave numbers may skip).
                                             return WaveItem{next++, uint32_t(issued_items++ % tokens), first};
                                           }
                                           fc.stop();
                                           return {};
                                         }) &
            tbb::make_filter<WaveItem, WaveItem>(tbb::filter_mode::parallel,
                                                 [&](WaveItem item) {
                                                   const uint32_t wi = item.wave;
                                                   WaveDesc wave{order.data() + size_t(wi) * pixels_per_wave,
                                                                 uint32_t(std::min<size_t>(
                                                                     pixels_per_wave,
                                                                     order.size() - size_t(wi) * pixels_per_wave)),
                                                                 item.first, std::min(pass_spp, total_spp - item.first)};
                                                   // (a last pass cut short by the budget halved as it is)
                                                   wave.half_bit = halves_bit(wave.samples, split);
                                                   WaveOutput& out = outputs[item.slot];
                                                   out.clear();
                                                   if (adaptive.on())
                                                     choose_adaptive(adaptive, item.first / adaptive_spp, merging, film,
                                                                     uint64_t(order.size()) * pass_spp, wave, out,
                                                                     active[item.slot]);
                                                   if (wave.pixel_count > 0)
                                                     trace_wave(tracer, wave, *states.local(), out, hooks.timeline,
                                                                int64_t(unit_of(item.first, wi)));
                                                   film.prepare(out);
                                                   return item;
                                                 }) &
            tbb::make_filter<WaveItem, void>(tbb::filter_mode::serial_in_order, [&](WaveItem item) {
              // Items arrive in issue order, pass after pass: the first wave of
              // a new pass means the one before is complete.
              if (merged_pass_first != item.first) {
                if (merged_pass_first != kNoPass) pass_done(merged_pass_first);
                adaptive.measure_before(item.first / adaptive_spp);
                merged_pass_first = item.first;
              }
              const uint64_t unit = unit_of(item.first, item.wave);
              const WaveOutput& out = outputs[item.slot];
              TraceBuffer* track = hooks.timeline ? &hooks.timeline->pipeline() : nullptr;
              if (track) track->begin_wave(int64_t(unit));
              auto t0 = opt.collect_stats || track ? Clock::now() : Clock::time_point();
              {
                std::lock_guard<std::mutex> lock(cx.film_mutex);
                film.merge(out);
              }
              if (cx.strategies) cx.strategies->merge(out.strategies, film);
              if (cx.guiding) cx.guiding->deposit(out.guide, out.light_guide);
              if (opt.collect_stats) film_seconds += std::chrono::duration<double>(Clock::now() - t0).count();
              if (track) {
                const auto t1 = Clock::now();
                track->span("film merge", TraceCategory::Pipeline, t0, t1, int64_t(out.samples.size()));
                track->counter(kMergeQueue, t1, --hooks.timeline->merge_queue(), true);
                track->end_wave();
              }
              cx.done += out.samples.size();
              merged.insert(unit);
              checkpoints.maybe_write(film);
            }));
    bool ends = stop || first >= total_spp || first < segment_end;
    // the passes this pace reaches: is the next iteration worth learning?
    uint64_t passes = timed && checkpoints.elapsed() > 0
                          ? uint64_t(double(first / pass_spp) * opt.time_limit_seconds / checkpoints.elapsed())
                          : 0;
    if (hooks.share_learnt && cx.guiding && cx.guiding->learning()) {
      // Every process comes here once per iteration, also one that stops
      // inside it, and they learn the field of all their units together.
      // Each saves its piece first, so that no piece is two iterations
      // behind another and none lacks units whose sums the field holds
      // (GuidingField::restore_joined): a rank lost later leaves its
      // learnt units in its piece.
      if (checkpoints.enabled()) checkpoints.write(film);
      std::string sums = cx.guiding->learnt_sums();
      const uint8_t mine = ends ? uint8_t(1 | (cx.stop_requested() ? 2 : 0)) : 0;
      const uint8_t all = hooks.share_learnt(sums, mine, passes);
      if (all & 1) {
        stop = true;  // (also where another process stopped: this one stops with it)
        cx.peer_interrupted = (all & 2) != 0;
        break;
      }
      cx.guiding->take_learnt_sums(sums);
      ends = false;
    }
    if (ends) break;
    if (merged_pass_first != kNoPass) pass_done(merged_pass_first);
    merged_pass_first = kNoPass;
    cx.guiding->end_iteration();
    if (passes > 0) cx.guiding->expect_passes(passes);
  }
  // The last pass merged is complete unless the render stopped inside it.
  if (merged_pass_first != kNoPass && !stop) pass_done(merged_pass_first);
  gather_stats(states, film_seconds, cx.stats);
  return stop;
}

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
        if (eye_alone.split == kSplitAuto) set_split(scene, light_sampler, opt, eye_alone, res.stats, s.hooks);
        res.stats.split = cx.split = eye_alone.split;
        stopped = run(PathTracer(scene, light_sampler, eye_alone));
      } else {
        stopped = run(Bdpt(scene, light_sampler, bs));
      }
      if (bs.merging)  // the radius of the last pass traced (Bdpt::prepare_merging)
        res.stats.vcm_last_radius =
            bs.vcm_radius * std::pow(float(res.stats.vcm_last_first_sample + 1), 0.5f * (bs.vcm_alpha - 1.f));
    } else {
      PathTracerSettings ps = path_settings(scene, opt, s.region, planned_spp);
      if (ps.split == kSplitAuto) set_split(scene, light_sampler, opt, ps, res.stats, s.hooks);
      res.stats.split = cx.split = ps.split;
      stopped = run(PathTracer(scene, light_sampler, ps));
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
