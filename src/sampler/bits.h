// Bit-level helpers the samplers share: hashing to seeds, bit reversal,
// and a float in [0, 1) from 32 bits.
#pragma once

#include <cstdint>

#include "math/rng.h"

namespace lantern {

inline uint64_t hash_combine(uint64_t a, uint64_t b) { return mix64(a ^ mix64(b + 0x9E3779B97F4A7C15ULL)); }
inline uint64_t hash_combine(uint64_t a, uint64_t b, uint64_t c) { return hash_combine(hash_combine(a, b), c); }

// Bit reversal: a byte swap, then the bits within each byte.
inline uint64_t reverse_bits_in_bytes(uint64_t v) {
  v = ((v >> 1) & 0x5555555555555555ULL) | ((v & 0x5555555555555555ULL) << 1);
  v = ((v >> 2) & 0x3333333333333333ULL) | ((v & 0x3333333333333333ULL) << 2);
  return ((v >> 4) & 0x0F0F0F0F0F0F0F0FULL) | ((v & 0x0F0F0F0F0F0F0F0FULL) << 4);
}
inline uint64_t reverse_bits64(uint64_t v) { return reverse_bits_in_bytes(__builtin_bswap64(v)); }
inline uint32_t reverse_bits32(uint32_t v) { return uint32_t(reverse_bits_in_bytes(__builtin_bswap32(v))); }

// The top 24 bits, so the value is exactly representable and below 1.
inline float bits32_to_unit_float(uint32_t v) { return float(v >> 8) * 0x1p-24f; }

inline int ceil_log2(uint64_t n) {
  int k = 0;
  while ((uint64_t(1) << k) < n) ++k;
  return k;
}

// Interleaves the low 16 bits of x and y (x in the even bits): the Morton
// (Z-order) index of a pixel.
inline uint64_t morton_2d(uint32_t x, uint32_t y) {
  auto spread = [](uint64_t v) {
    v &= 0xFFFF;
    v = (v | (v << 8)) & 0x00FF00FFULL;
    v = (v | (v << 4)) & 0x0F0F0F0FULL;
    v = (v | (v << 2)) & 0x33333333ULL;
    v = (v | (v << 1)) & 0x55555555ULL;
    return v;
  };
  return spread(x) | (spread(y) << 1);
}

}  // namespace lantern
