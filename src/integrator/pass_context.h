// What a render's drivers (run_passes.h's passes, metropolis.cpp's chains)
// work with besides the integrator: the film, the counters, the stop.
#pragma once

#include <atomic>
#include <functional>
#include <mutex>

#include "film/film.h"
#include "film/strategy_film.h"
#include "integrator/guiding_field.h"
#include "integrator/render_checkpoints.h"
#include "integrator/wave_stats.h"
#include "lantern/render.h"
#include "scene/scene.h"

namespace lantern {

class RayDump;

// What run_passes works with, besides the integrator.
struct PassContext {
  const Scene& scene;
  const RenderOptions& opt;
  const RenderHooks& hooks;
  RayCounters& counters;
  Film& film;
  std::mutex& film_mutex;  // held while a wave is merged (RenderSession::snapshot reads under it)
  StrategyFilm* strategies;
  std::atomic<uint64_t>& done;
  RenderStats& stats;
  RayDump* dump;
  Checkpointer& checkpoints;
  GuidingField* guiding;  // null: paths are not guided
  const std::atomic<bool>& cancelled;  // RenderSession::cancel
  uint32_t split = 1;                  // the path tracer's paths per camera sample (PathTracerSettings::split)
  // A guided path tracer's split once its field has learnt: chooses it (the
  // split pilot, if asked for), sets it in the tracer and returns it
  // (pass_layout.h). Empty for other integrators.
  std::function<uint32_t()> unguided_split = {};
  bool peer_interrupted = false;       // another process of the render was interrupted (RenderHooks::share_learnt)
  bool stop_requested() const { return cancelled.load() || (hooks.cancel && hooks.cancel->load()); }
};

// A thread's wave state for `tracer`, with room for `capacity` paths.
template <class Tracer>
auto make_thread_state(const Tracer& tracer, uint32_t capacity, const PassContext& cx) {
  auto state = tracer.make_wave_state(capacity, RayStream(cx.scene.accel->handle(), cx.opt.ray_backend, &cx.counters));
  state->stats.timing = cx.opt.collect_stats;
  state->stream.set_timing(cx.opt.collect_stats);
  state->stream.set_dump(cx.dump);
  state->stream.set_scene(cx.scene.accel->instance_base(), &cx.scene.shapes);
  return state;
}

// Sums what the threads' wave states measured.
template <class States>
void gather_stats(States& states, double film_seconds, RenderStats& st) {
  WaveStats total;
  std::array<double, 4> ray_seconds{};
  for (auto& state : states) {
    total += state->stats;
    for (size_t k = 0; k < 4; ++k) ray_seconds[k] += state->stream.seconds()[k];
    st.wave_pool_bytes += state->memory_bytes();
    ++st.threads;
  }
  st.eye_vertices = total.eye_vertices;
  st.light_vertices = total.light_vertices;
  st.light_samples = total.light_samples;
  st.light_samples_unoccluded = total.light_samples_unoccluded;
  st.merges = total.merges;
  st.vcm_grid_seconds = total.grid_seconds;
  st.vcm_last_first_sample = total.last_pass;
  for (int e = 0; e < kPathEndCount; ++e) {
    st.eye_ends.emplace_back(path_end_name(PathEnd(e)), total.eye_ends[size_t(e)]);
    st.light_ends.emplace_back(path_end_name(PathEnd(e)), total.light_ends[size_t(e)]);
  }
  st.timed = states.begin() != states.end() && (*states.begin())->stats.timing;
  if (!st.timed) return;
  for (int k = 0; k < kStageCount; ++k)  // the stages this integrator has
    if (total.seconds[size_t(k)] > 0.0) st.stage_seconds.emplace_back(stage_name(Stage(k)), total.seconds[size_t(k)]);
  st.camera_ray_seconds = ray_seconds[size_t(RayKind::Camera)];
  st.extension_ray_seconds = ray_seconds[size_t(RayKind::Extension)];
  st.light_ray_seconds = ray_seconds[size_t(RayKind::LightExtension)];
  st.shadow_ray_seconds = ray_seconds[size_t(RayKind::Shadow)];
  st.film_seconds = film_seconds;
}

}  // namespace lantern
