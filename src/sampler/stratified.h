// pbrt-v4's stratified sampler: xsamples x ysamples strata per pixel; each
// dimension visits them in its own random order (so dimensions are not
// correlated), with a jittered point in each stratum (or its centre).
#pragma once

#include <cstdint>

#include "math/common.h"
#include "sampler/bits.h"
#include "sampler/permutation.h"

namespace lantern {

inline float jitter_offset(bool jitter, uint64_t h) { return jitter ? bits_to_unit_float(mix64(h)) : 0.5f; }

inline float stratified_1d(uint32_t i, uint32_t n, bool jitter, uint64_t dim_hash) {
  uint32_t stratum = permutation_element(i, n, dim_hash);
  return min_num((float(stratum) + jitter_offset(jitter, dim_hash ^ i)) / float(n), kOneMinusEpsilon);
}

inline Vec2 stratified_2d(uint32_t i, uint32_t xs, uint32_t ys, bool jitter, uint64_t dim_hash) {
  uint32_t stratum = permutation_element(i, xs * ys, dim_hash);
  float ux = jitter_offset(jitter, dim_hash ^ i), uy = jitter_offset(jitter, ~dim_hash ^ i);
  return Vec2(min_num((float(stratum % xs) + ux) / float(xs), kOneMinusEpsilon),
              min_num((float(stratum / xs) + uy) / float(ys), kOneMinusEpsilon));
}

}  // namespace lantern
