// A random hierarchical permutation of sample indices: bit b of the index
// is flipped or not according to a hash of the bits above it. Such a
// permutation maps every aligned block of 2^k indices onto an aligned block
// of 2^k indices, so a pixel's first 2^k samples stay one aligned block of
// the Sobol sequence (a (0, k, 2)-net in dimensions 0 and 1), and
// neighbouring pixels' blocks stay inside a common larger block.
//
// The flips come from a Laine-Karras style hash (x ^= x * even constant:
// each bit changes only with the bits below it) on the bit-reversed index,
// as Burley (2020) does for values: one hash for all bits instead of one per
// digit. Only the low `bits` bits of the result are used.
#pragma once

#include <cstdint>

#include "sampler/bits.h"

namespace lantern {

// From the index's bits already reversed (reverse_bits64(index)): a
// sampler that draws many dimensions of one index reverses it once
// (PathSampler keeps zsobol's key so).
inline uint64_t nested_scramble_reversed_index(uint64_t reversed_index, int bits, uint64_t seed) {
  uint64_t x = reversed_index + seed;
  x ^= x * 0x9E3779B97F4A7C14ULL;
  x ^= x * 0xBF58476D1CE4E5B8ULL;
  x ^= x * 0x94D049BB133111EAULL;
  x ^= x * 0xD6E8FEB86659FD92ULL;
  x = reverse_bits64(x);
  return bits >= 64 ? x : x & ((uint64_t(1) << bits) - 1);
}

inline uint64_t nested_scramble_index(uint64_t index, int bits, uint64_t seed) {
  return nested_scramble_reversed_index(reverse_bits64(index), bits, seed);
}

}  // namespace lantern
