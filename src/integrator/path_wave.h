// Structure-of-arrays pools of the path tracer's wave. Arrays indexed by
// slot hold per-path state; arrays indexed by ray hold per-bounce data for
// the active paths (ray i belongs to slot active[i]).
#pragma once

#include <vector>

#include "accel/ray_stream.h"
#include "integrator/hit.h"
#include "integrator/wave_stats.h"
#include "material/material.h"
#include "sampler/sampler.h"

namespace lantern {

struct PathWave {
  explicit PathWave(uint32_t capacity, RayStream s) : stream(std::move(s)) { resize(capacity); }

  // per slot
  std::vector<uint32_t> pixel;
  std::vector<PathSampler> sampler;
  std::vector<RGB> beta, L;
  std::vector<float> prev_pdf, eta_scale;
  std::vector<Vec3> prev_p;  // origin of the ray that found the current vertex
  std::vector<Vec3> prev_n;  // its shading normal (the light sampler's context; zero at the camera)
  std::vector<uint8_t> prev_specular;
  uint32_t depth = 0;  // all active paths share the bounce count

  // per ray of the current bounce
  std::vector<uint32_t> active;
  RayBatch rays;
  HitPool hits;

  // next-event estimation
  RayBatch shadow;
  std::vector<uint32_t> shadow_slot;
  std::vector<RGB> shadow_contrib;

  RayStream stream;
  WaveStats stats;

  size_t memory_bytes() const {
    return vector_bytes(pixel) + vector_bytes(sampler) + vector_bytes(beta) + vector_bytes(L) + vector_bytes(prev_pdf) +
           vector_bytes(eta_scale) + vector_bytes(prev_p) + vector_bytes(prev_n) + vector_bytes(prev_specular) + vector_bytes(active) +
           rays.memory_bytes() + hits.memory_bytes() + shadow.memory_bytes() + vector_bytes(shadow_slot) +
           vector_bytes(shadow_contrib);
  }

  void resize(uint32_t n) {
    for (auto* v : {&pixel, &active, &shadow_slot}) v->resize(n);
    sampler.resize(n);
    for (auto* v : {&beta, &L, &shadow_contrib}) v->resize(n);
    for (auto* v : {&prev_pdf, &eta_scale}) v->resize(n);
    prev_p.resize(n);
    prev_n.resize(n);
    prev_specular.resize(n);
    hits.resize(n);
    rays.reserve(n);
    shadow.reserve(n);
  }
};

}  // namespace lantern
