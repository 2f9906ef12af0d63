// Counter-based random numbers: every value is a pure function of
// (seed, pixel, sample index, dimension). No state is shared between paths,
// so an image does not depend on how the work is scheduled over threads.
#pragma once

#include <cstdint>

#include "math/common.h"

namespace lantern {

// A 64-bit finaliser with good avalanche (the "moremur" constants, a
// published variant of the MurmurHash3 / SplitMix64 mixer).
inline uint64_t mix64(uint64_t x) {
  x ^= x >> 27;
  x *= 0x3C79AC492BA7B653ULL;
  x ^= x >> 33;
  x *= 0x1C69B3F74AC4AE35ULL;
  x ^= x >> 27;
  return x;
}

inline uint64_t hash_key(uint64_t seed, uint64_t pixel, uint64_t sample_index) {
  uint64_t h = mix64(seed + 0x9E3779B97F4A7C15ULL);
  h = mix64(h ^ (pixel + 0xD1B54A32D192ED03ULL));
  return mix64(h ^ (sample_index * 0xABC98388FB8FAC03ULL + 0x8CB92BA72F3D8DD7ULL));
}

// Uniform float in [0, 1) from the top 24 bits.
inline float bits_to_unit_float(uint64_t bits) {
  return float(bits >> 40) * 0x1p-24f;
}

// The per-path sampler: a key that names the sample, and the next dimension.
struct PathSampler {
  uint64_t key = 0;
  uint32_t dimension = 0;

  static PathSampler make(uint64_t seed, uint64_t pixel, uint64_t sample_index) {
    return PathSampler{hash_key(seed, pixel, sample_index), 0};
  }
  float get1d() {
    return bits_to_unit_float(mix64(key ^ (uint64_t(dimension++) * 0x9E3779B97F4A7C15ULL)));
  }
  Vec2 get2d() {
    float a = get1d();
    return Vec2(a, get1d());
  }
};

}  // namespace lantern
