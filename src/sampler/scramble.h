// Randomisations of base-2 digits (pbrt-v4's names): every one maps the
// points of a (t, m, s)-net to a net with the same t, so stratification
// survives while the points become an unbiased random sample.
#pragma once

#include <cstdint>

#include "sampler/bits.h"

namespace lantern {

enum class Randomization : uint8_t { None, PermuteDigits, FastOwen, Owen };

// Random digit permutation: in base 2 a permutation of a digit is either the
// identity or a flip, so one xor with random bits (Kollig & Keller 2002).
inline uint32_t permute_binary_digits(uint32_t v, uint32_t seed) { return v ^ seed; }

// Burley 2020, "Practical Hash-based Owen Scrambling" (JCGT 9(4)): a hash
// that is a nested uniform scramble of the reversed bits, since each bit of
// the product only depends on the bits below it.
inline uint32_t laine_karras_hash(uint32_t v, uint32_t seed) {
  v += seed;
  v ^= v * 0x6c50b47cu;
  v ^= v * 0xb82f1e52u;
  v ^= v * 0xc7afe638u;
  v ^= v * 0x8d22f6e6u;
  return v;
}
inline uint32_t fast_owen_scramble(uint32_t v, uint32_t seed) {
  return reverse_bits32(laine_karras_hash(reverse_bits32(v), seed));
}

// Owen 1995: digit b is flipped or not by a random bit that depends on all
// the digits above it, one hash per digit.
inline uint32_t owen_scramble(uint32_t v, uint32_t seed) {
  uint32_t out = v;
  for (int b = 0; b < 32; ++b) {
    uint64_t prefix = b == 0 ? 0 : uint64_t(v >> (32 - b));
    if (mix64((prefix << 6 | uint64_t(b)) ^ (uint64_t(seed) << 38) ^ seed) & 1) out ^= 1u << (31 - b);
  }
  return out;
}

inline uint32_t scramble_bits(uint32_t v, Randomization r, uint32_t seed) {
  switch (r) {
    case Randomization::None: return v;
    case Randomization::PermuteDigits: return permute_binary_digits(v, seed);
    case Randomization::FastOwen: return fast_owen_scramble(v, seed);
    case Randomization::Owen: return owen_scramble(v, seed);
  }
  return v;
}

// Dimension 0 of the Sobol sequence (the index's bits reversed), scrambled:
// for fastowen the two reversals cancel.
inline uint32_t scrambled_van_der_corput(uint64_t index, Randomization r, uint32_t seed) {
  if (r == Randomization::FastOwen) return reverse_bits32(laine_karras_hash(uint32_t(index), seed));
  return scramble_bits(reverse_bits32(uint32_t(index)), r, seed);
}

}  // namespace lantern
