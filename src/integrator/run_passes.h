// The render loop (render.cpp's RenderSession::render_all runs it): one
// integrator's waves, pass after pass, through a oneTBB pipeline whose last
// stage adds them to the film, laid out as integrator/pass_layout.h says.
//
// Determinism: a pass covers a fixed range of sample indices for every
// pixel; waves record their samples and splats in slot order, and the film
// merges whole waves in wave order. So every sum is formed in the same order
// whatever the thread count, and random numbers depend only on (seed, pixel,
// sample index, dimension).
#pragma once

#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_pipeline.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "integrator/adaptive_sampling.h"
#include "integrator/pass_context.h"
#include "integrator/pass_layout.h"
#include "integrator/ticket_cursor.h"
#include "integrator/wave_stats.h"
#include "trace/timeline.h"

namespace lantern {

inline constexpr const char* kMergeQueue = "waves waiting for the film merge";

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
inline void choose_adaptive(const AdaptivePasses& adaptive, uint32_t pass, bool merging, const Film& film,
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

// Where a guided render's passes give way to an unguided render's once
// its field has learnt (pass_layout.h): from sample `from` on, passes of
// `pass_spp`, the path tracer's camera samples split in `split` paths,
// whether its guide stopped or goes on (the split pilot runs then, if
// asked for).
struct Relayout {
  uint32_t from, pass_spp, split;
};
// `reach`: the samples per pixel the render reaches, its mean under an
// adaptive budget.
inline Relayout plan_relayout(PassContext& cx, bool merging, bool timed, bool adaptive, uint32_t total_spp,
                              uint32_t reach) {
  const GuidingField& field = *cx.guiding;
  auto from_for = [&](uint32_t pass_spp) {
    return uint32_t(std::min<uint64_t>(relayout_from(field.learnt_passes(), pass_spp, adaptive), UINT32_MAX));
  };
  // The split is chosen only where passes of more than one sample follow:
  // under --spp their size does not depend on it.
  uint32_t split = cx.split;
  if (cx.unguided_split && (timed || from_for(pass_samples(merging, false, false, adaptive, 1, total_spp)) < reach))
    split = cx.unguided_split();
  const uint32_t pass_spp = pass_samples(merging, false, timed, adaptive, split, total_spp);
  return {from_for(pass_spp), pass_spp, split};
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
  const bool merging = merges_vertices(opt.integrator);
  const uint32_t pixels = uint32_t(order.size());
  PassLayout layout = pass_layout(pass_samples(merging, bool(cx.guiding), timed, goal.on(), cx.split, total_spp),
                                  pixels, merging, opt.wave_size);
  // A guided render's passes give way to an unguided render's once its
  // field has learnt (pass_layout.h): room in the waves for those too.
  bool relaid = !cx.guiding || merging;
  const uint32_t capacity =
      relaid ? layout.capacity() : std::max({layout.capacity(), uint32_t(std::max(opt.wave_size, 1)), 16u});
  // A checkpoint's bound on its units: until a guided render's layout is
  // known (its relayout, or its end), the most any relayout may number
  // (the passes after one are of min(total_spp, 16), whatever the split);
  // then its own count, which --part's film files and merges read.
  const bool bounded = !relaid && !timed;
  if (!bounded)
    checkpoints.set_units(timed ? 0 : (total_spp + layout.pass_spp - 1) / layout.pass_spp, layout.waves);
  else
    checkpoints.set_units(most_guided_units(layout, pass_samples(merging, false, false, goal.on(), 1, total_spp),
                                            pixels, merging, opt.wave_size, total_spp, goal.on()),
                          1);

  using State = typename decltype(tracer.make_wave_state(0, RayStream(nullptr, backend, nullptr)))::element_type;
  // Units: waves numbered through the whole render (passes one after
  // another). This run renders those of its share that the film lacks.
  auto unit_of = [&](uint32_t first, uint32_t wi) { return layout.unit_of(first, wi); };
  // The units done when this run began (of every process: the others'
  // too, for MPI's ranks that did not read the checkpoint): the serial
  // merge stage adds to this process's live set while the input stage, on
  // another thread, reads that separate one (units of this run are never
  // offered twice: the walk only moves on).
  const UnitShare share{opt.share_index, opt.share_count};
  UnitSet& merged = checkpoints.done();
  const UnitSet& done_before = checkpoints.done_before();
  auto wanted = [&](uint32_t first, uint32_t wi) {
    return share.holds(layout.pass_of(first), wi) && !done_before.contains(unit_of(first, wi));
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
  auto pipeline_passes = [&] { return layout.pass_spp == 1 ? 2u : 1u; };  // in a pass of adaptive sampling
  AdaptivePasses adaptive(film, cx.film_mutex, order, layout.pixels_per_wave, layout.pass_spp * pipeline_passes(),
                          goal);
  const size_t most_tokens = 2 * size_t(std::max(1, tbb::this_task_arena::max_concurrency()));
  auto tokens_now = [&] {  // (each segment's pipeline starts empty, so its layout's)
    return adaptive.on() ? std::min<size_t>(most_tokens, size_t(layout.waves) * pipeline_passes()) : most_tokens;
  };
  std::vector<WaveOutput> outputs(most_tokens);
  for (WaveOutput& o : outputs) o.keep_spectra = film.buckets().count > 0;  // Film "spectral"
  std::vector<std::vector<uint32_t>> active(adaptive.on() ? most_tokens : 0);  // each slot's pixels that take the pass

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
    if (hooks.pass_done) hooks.pass_done(pass_first + std::min(layout.pass_spp, total_spp - pass_first));
  };
  auto advance_pass = [&] {
    first += layout.pass_spp;
    next = 0;
    return first < total_spp;
  };
  // While a guiding field learns, the pipeline stops at the end of each of
  // its iterations (the waves drain, the field is updated) and starts again.
  // Once it has learnt, the passes of one sample go on to where the
  // unguided render's passes begin (relayout_from), and those take over.
  std::optional<Relayout> relayout;
  auto end_of_segment = [&]() -> uint64_t {
    if (cx.guiding && cx.guiding->learning()) return cx.guiding->iteration_end() * layout.pass_spp;
    if (relaid) return UINT64_MAX;
    if (!relayout) {
      relayout = plan_relayout(cx, merging, timed, goal.on(), total_spp, budgeted ? uint32_t(opt.spp) : total_spp);
      adaptive.relayout(relayout->from, relayout->pass_spp);
    }
    if (first < relayout->from) return relayout->from;
    if (relayout->pass_spp != layout.pass_spp)
      layout = pass_layout(relayout->pass_spp, pixels, merging, opt.wave_size, &layout, relayout->from);
    if (bounded) checkpoints.set_units(layout.units_to(total_spp), 1);
    cx.split = relayout->split;
    relaid = true;
    return UINT64_MAX;
  };
  for (uint64_t segment_end = end_of_segment();; segment_end = end_of_segment()) {
    const bool learning = cx.guiding && cx.guiding->learning();
    const size_t tokens = tokens_now();
    tbb::parallel_pipeline(
        tokens,
        tbb::make_filter<void, WaveItem>(tbb::filter_mode::serial_in_order, [&](tbb::flow_control& fc) -> WaveItem {
          // A time budget shorter than the set-up still
          // renders one wave, so every run adds samples.
          // Without tickets the next unit is found before a
          // stop is looked at, so a stop after the last unit is
          // no interruption; with them, after, so that no
          // ticket is taken that will not be rendered.
          const bool ticketed = bool(hooks.next_ticket);
          for (;;) {
            if (first >= total_spp || first >= segment_end || adaptive.reached(adaptive.pass_of(first))) break;
            if (!ticketed && !tickets.next(first, next, layout.waves, wanted)) {
              if (advance_pass()) continue;
              break;  // the last pass is done
            }
            if (stop || cx.stop_requested() || (issued && time_is_up())) {
              stop = true;
              break;
            }
            if (ticketed && !tickets.next(first, next, layout.waves, wanted)) {
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
        }) & tbb::make_filter<WaveItem, WaveItem>(tbb::filter_mode::parallel, [&](WaveItem item) {
          const uint32_t wi = item.wave;
          const uint32_t ppw = layout.pixels_per_wave;
          WaveDesc wave{order.data() + size_t(wi) * ppw,
                        uint32_t(std::min<size_t>(ppw, order.size() - size_t(wi) * ppw)), item.first,
                        std::min(layout.pass_spp, total_spp - item.first)};
          // (a last pass cut short by the budget halved as it is)
          wave.half_bit = halves_bit(wave.samples, cx.split);
          WaveOutput& out = outputs[item.slot];
          out.clear();
          if (adaptive.on())
            choose_adaptive(adaptive, adaptive.pass_of(item.first), merging, film, uint64_t(pixels) * layout.pass_spp,
                            wave, out, active[item.slot]);
          if (wave.pixel_count > 0)
            trace_wave(tracer, wave, *states.local(), out, hooks.timeline, int64_t(unit_of(item.first, wi)));
          film.prepare(out);
          return item;
        }) & tbb::make_filter<WaveItem, void>(tbb::filter_mode::serial_in_order, [&](WaveItem item) {
          // Items arrive in issue order, pass after pass: the first wave of
          // a new pass means the one before is complete.
          if (merged_pass_first != item.first) {
            if (merged_pass_first != kNoPass) pass_done(merged_pass_first);
            adaptive.measure_before(adaptive.pass_of(item.first));
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
                          ? uint64_t(double(layout.pass_of(first)) * opt.time_limit_seconds / checkpoints.elapsed())
                          : 0;
    if (hooks.share_learnt && learning) {
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
    if (!learning) continue;  // (the passes of one sample up to a relayout)
    cx.guiding->end_iteration();
    if (passes > 0) cx.guiding->expect_passes(passes);
  }
  // The last pass merged is complete unless the render stopped inside it.
  if (merged_pass_first != kNoPass && !stop) pass_done(merged_pass_first);
  if (bounded && !stop) checkpoints.set_units(layout.units_to(total_spp), 1);  // (no relayout came)
  gather_stats(states, film_seconds, cx.stats);
  return stop;
}

}  // namespace lantern
