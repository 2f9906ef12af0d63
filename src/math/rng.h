// Counter-based random numbers: hashes of the values that name a sample,
// with no state shared between paths (sampler/sampler.h builds on them).
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

// A stream of independent uniform numbers named by three integers, for
// tests and tools that need random numbers outside a render's sampler.
struct RandomStream {
  uint64_t key = 0;
  uint32_t counter = 0;

  static RandomStream make(uint64_t seed, uint64_t a, uint64_t b) { return RandomStream{hash_key(seed, a, b), 0}; }
  float get1d() { return bits_to_unit_float(mix64(key ^ (uint64_t(counter++) * 0x9E3779B97F4A7C15ULL))); }
  Vec2 get2d() {
    float a = get1d();
    return Vec2(a, get1d());
  }
};

}  // namespace lantern
