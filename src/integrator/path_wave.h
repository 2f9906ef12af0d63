// Structure-of-arrays pools of the path tracer's wave. Arrays indexed by
// slot hold per-path state; arrays indexed by ray hold per-bounce data for
// the active paths (ray i belongs to slot active[i]).
#pragma once

#include <vector>

#include "accel/ray_stream.h"
#include "integrator/guide_vertices.h"
#include "integrator/hit.h"
#include "integrator/medium_events.h"
#include "integrator/vertex.h"
#include "integrator/wave_stats.h"
#include "light/lights.h"
#include "material/material.h"
#include "sampler/sampler.h"

namespace lantern {

struct PathWave {
  explicit PathWave(uint32_t capacity, RayStream s) : stream(std::move(s)) { resize(capacity); }

  // per slot
  std::vector<uint32_t> pixel;
  std::vector<PathSampler> sampler;
  std::vector<Spectrum> beta, L;
  std::vector<SampledWavelengths> lambda;
  std::vector<float> time;  // in the shutter (integrator/shutter.h)
  std::vector<float> prev_pdf, eta_scale;
  std::vector<Vec3> prev_p;  // origin of the ray that found the current vertex
  std::vector<Vec3> prev_n;  // its shading normal (the light sampler's context; zero at the camera)
  std::vector<uint8_t> prev_specular;
  std::vector<uint8_t> dispersed;  // scattered at a dispersive surface (integrator/dispersion.h)
  // A camera sample split at its first hit (PathTracerSettings::split):
  // per slot, the slot of its camera sample's first path (the leader,
  // itself when not split), and the leader's numbers for the camera sample
  // and the first hit's next-event estimation; `split` when the wave has
  // such groups.
  std::vector<uint32_t> leader;
  std::vector<PathSampler> camera_sampler;
  bool split = false;
  uint32_t slots = 0;  // of the wave being traced
  // The segments all active paths have: 1 at the first hit, as bdpt counts
  // (bdpt_wave.h). The sample dimensions are laid out by bounce (depth - 1).
  uint32_t depth = 1;
  uint32_t bounce() const { return depth - 1; }

  // per ray of the current bounce
  std::vector<uint32_t> active;
  RayBatch rays;
  HitPool hits;

  // next-event estimation
  RayBatch shadow;
  std::vector<uint32_t> shadow_slot;
  std::vector<Spectrum> shadow_contrib;

  // Participating media (empty in a scene without them): per slot, the
  // medium the path's ray travels in; per ray, the distance numbers, where
  // the segments ended, and the rays that scattered in a medium; per shadow
  // ray, its medium, transmittance, and the densities its MIS weight waits
  // for (the transmittance enters the BSDF strategy's density).
  std::vector<MediumHandle> medium, ray_medium;
  std::vector<float> u_distance;
  std::vector<SampledWavelengths> ray_lambda, shadow_lambda;
  SegmentEnds ends;
  std::vector<uint32_t> scattered;
  std::vector<MediumHandle> shadow_medium;
  std::vector<Spectrum> shadow_T, shadow_T_mis;  // the estimate, and what MIS sees (medium_events.h)
  std::vector<float> shadow_light_pdf, shadow_scatter_pdf;  // light_pdf 0: a delta light, weight 1
  // A sample of an emissive medium: the medium the ray must end in, and
  // the extinction there (zero for other lights).
  std::vector<MediumHandle> shadow_expect;
  std::vector<Spectrum> shadow_sigma_end;
  CrossingScratch crossing;

  GuideVertices guide;  // while the guiding field learns

  RayStream stream;
  WaveStats stats;

  void resize_media(uint32_t n) {
    medium.resize(n);
    ray_medium.resize(n);
    u_distance.resize(n);
    ray_lambda.resize(n);
    shadow_lambda.resize(n);
    ends.resize(n);
    scattered.reserve(n);
    shadow_medium.resize(n);
    shadow_T.resize(n);
    shadow_T_mis.resize(n);
    shadow_light_pdf.resize(n);
    shadow_scatter_pdf.resize(n);
    shadow_expect.resize(n);
    shadow_sigma_end.resize(n);
  }

  size_t memory_bytes() const {
    return vector_bytes(pixel) + vector_bytes(sampler) + vector_bytes(leader) + vector_bytes(camera_sampler) +
           vector_bytes(beta) + vector_bytes(L) + vector_bytes(lambda) + vector_bytes(time) + vector_bytes(prev_pdf) +
           vector_bytes(eta_scale) + vector_bytes(prev_p) + vector_bytes(prev_n) + vector_bytes(prev_specular) +
           vector_bytes(active) + rays.memory_bytes() + hits.memory_bytes() + shadow.memory_bytes() +
           vector_bytes(shadow_slot) + vector_bytes(shadow_contrib) + vector_bytes(medium) + vector_bytes(ray_medium) +
           vector_bytes(u_distance) + vector_bytes(ray_lambda) + vector_bytes(shadow_lambda) + ends.memory_bytes() +
           vector_bytes(scattered) + vector_bytes(shadow_medium) + vector_bytes(shadow_T) + vector_bytes(shadow_T_mis) +
           vector_bytes(shadow_light_pdf) + vector_bytes(shadow_scatter_pdf) + vector_bytes(shadow_expect) +
           vector_bytes(shadow_sigma_end) + crossing.memory_bytes() + guide.memory_bytes();
  }

  void resize(uint32_t n) {
    for (auto* v : {&pixel, &active, &shadow_slot, &leader}) v->resize(n);
    sampler.resize(n);
    camera_sampler.resize(n);
    for (auto* v : {&beta, &L, &shadow_contrib}) v->resize(n);
    lambda.resize(n);
    for (auto* v : {&time, &prev_pdf, &eta_scale}) v->resize(n);
    prev_p.resize(n);
    prev_n.resize(n);
    prev_specular.resize(n);
    dispersed.resize(n);
    hits.resize(n);
    rays.reserve(n);
    shadow.reserve(n);
  }
};

// A shadow ray of a scene with media, from o towards light sample ls,
// starting in medium m; its MIS weight is formed once its transmittance is
// known (light_pdf 0: a delta light). A sample of an emissive medium
// counts only if the ray ends in `expect`, of extinction sigma_end there.
inline void push_media_shadow_ray(PathWave& w, uint32_t slot, const Vec3& o, const LightSample& ls, MediumHandle m,
                                  float light_pdf, float scatter_pdf, const Spectrum& unweighted,
                                  MediumHandle expect = {}, const Spectrum& sigma_end = Spectrum(0.f)) {
  uint32_t r;
  if (ls.infinite) {
    r = w.shadow.push(o, ls.wi, 0.f, kInfinity, w.time[slot]);
  } else {
    r = w.shadow.push(o, light_sample_target(ls) - o, 0.f, 1.f, w.time[slot]);
  }
  w.shadow_slot[r] = slot;
  w.shadow_contrib[r] = unweighted;
  w.shadow_medium[r] = m;
  w.shadow_light_pdf[r] = light_pdf;
  w.shadow_scatter_pdf[r] = scatter_pdf;
  w.shadow_expect[r] = expect;
  w.shadow_sigma_end[r] = sigma_end;
  w.shadow_lambda[r] = w.lambda[slot];
}

}  // namespace lantern
