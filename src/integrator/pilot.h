// The short renders bdpt runs before its own to choose how it renders
// (light_subpath_rate.h, eye_subpaths_alone.h): waves of a given list of
// pixels traced a batch at a time, their outputs read in wave order (so
// that sums are the same whatever the threads) and then freed.
#pragma once

#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <vector>

#include "film/film.h"
#include "integrator/wave.h"
#include "integrator/wave_stats.h"
#include "scene/scene.h"

namespace lantern {

inline constexpr uint32_t kPilotWaveSlots = 1024;
inline constexpr size_t kPilotBatch = 8;  // waves

// Whether a render pays for a pilot of pilot_samples camera samples (or
// paths): it renders 16 times as many or more over its own pixels (a crop
// window's; every part's and MPI rank's whole image, so all of them
// answer alike), or has a time budget (planned_spp 0), where each pilot
// weighs its time itself. A pilot costing more than a sixteenth of the
// render cannot win back its cost from the gains it chooses among.
inline bool render_pays_for_pilot(uint32_t planned_spp, int width, int height, double pilot_samples) {
  return planned_spp == 0 || double(planned_spp) * double(width) * double(height) >= 16.0 * pilot_samples;
}

// A pilot's settings from a render's (BdptSettings, PathTracerSettings):
// an image of width x height of its own, not a part of another, planned
// for spp samples per pixel.
template <class Settings>
Settings pilot_settings(const Settings& render, int width, int height, uint32_t spp) {
  Settings s = render;
  s.width = width;
  s.height = height;
  s.full_width = s.full_height = 0;
  s.raster_offset = Vec2(0.f);
  s.planned_spp = spp;
  return s;
}

// Traces spp samples of each of `pixels` with `tracer` and hands each wave,
// the index in `pixels` of its first pixel and its output to `read`.
// Returns the waves' stats, summed.
template <class Tracer, class Read>
WaveStats trace_pilot(const Scene& scene, const Tracer& tracer, const std::vector<uint32_t>& pixels, uint32_t spp,
                      RayBackend backend, Read&& read) {
  const uint32_t per_wave = std::max(1u, kPilotWaveSlots / spp);
  const size_t waves = (pixels.size() + per_wave - 1) / per_wave;
  auto wave_at = [&](size_t i) {
    return WaveDesc{pixels.data() + i * per_wave, uint32_t(std::min<size_t>(per_wave, pixels.size() - i * per_wave)), 0u,
                    spp};
  };
  std::vector<WaveOutput> outputs(kPilotBatch);
  using State = decltype(tracer.make_wave_state(0, RayStream(scene.accel->handle(), backend, nullptr)));
  tbb::enumerable_thread_specific<State> states([&] {
    State s = tracer.make_wave_state(per_wave * spp, RayStream(scene.accel->handle(), backend, nullptr));
    s->stream.set_scene(scene.accel->instance_base(), &scene.shapes);
    return s;
  });
  for (size_t first = 0; first < waves; first += kPilotBatch) {
    const size_t n = std::min(kPilotBatch, waves - first);
    tbb::parallel_for(size_t(0), n, [&](size_t i) {
      outputs[i].clear();
      tracer.trace(wave_at(first + i), *states.local(), outputs[i]);
    });
    for (size_t i = 0; i < n; ++i) read(wave_at(first + i), (first + i) * per_wave, outputs[i]);
  }
  WaveStats total;
  for (const State& s : states) total += s->stats;
  return total;
}

}  // namespace lantern
