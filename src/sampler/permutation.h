// Random permutations of [0, n) evaluated one element at a time, without
// tables: a bijection of the enclosing power-of-two range built from
// invertible steps (xor with a constant, multiplication by an odd number,
// xor with a right shift, all modulo 2^k), walked along its cycle until
// the value falls inside [0, n) ("cycle walking", as in format-preserving
// encryption). Expected steps: fewer than 2.
#pragma once

#include <cstdint>

#include "sampler/bits.h"

namespace lantern {

inline uint32_t permutation_element(uint32_t i, uint32_t n, uint64_t seed) {
  if (n <= 1) return 0;
  const int k = ceil_log2(n);
  const uint32_t mask = k >= 32 ? ~0u : (1u << k) - 1u;
  const int shift = (k + 1) / 2;
  const uint64_t h1 = mix64(seed), h2 = mix64(h1 + 0x632BE59BD9B4E019ULL);
  do {
    i ^= uint32_t(h1);
    i = (i * (uint32_t(h1 >> 32) | 1u)) & mask;
    i ^= i >> shift;
    i = (i * (uint32_t(h2) | 1u)) & mask;
    i ^= uint32_t(h2 >> 32) & mask;
    i = (i * 0x2C1B3C6Du) & mask;  // odd
    i ^= i >> shift;
  } while (i >= n);
  return i;
}

}  // namespace lantern
