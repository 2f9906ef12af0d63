// Sobol generator matrices over GF(2), one 32-bit column per bit of the
// sample index, from Joe & Kuo's direction numbers (2008, "Constructing
// Sobol sequences with better two-dimensional projections") as Boost.Random
// ships them.
#pragma once

#include <cstdint>

#include "sampler/bits.h"

namespace lantern {

inline constexpr int kSobolDimensions = 1024;
inline constexpr int kSobolColumns = 52;  // indices below 2^52

// Column c of dimension d's matrix is sobol_matrix(d)[c].
const uint32_t* sobol_matrix(int dimension);

// The Sobol point's 32 bits: the xor of the columns of the index's set bits
// (visited by counting trailing zeros: as many steps as set bits).
inline uint32_t sobol_bits(uint64_t index, int dimension) {
  const uint32_t* m = sobol_matrix(dimension);
  index &= (uint64_t(1) << kSobolColumns) - 1;
  uint32_t v = 0;
  for (; index != 0; index &= index - 1) v ^= m[__builtin_ctzll(index)];
  return v;
}

// Dimensions 0 and 1 are what the per-pixel samplers use: the van der
// Corput sequence (the identity matrix, bit reversed) and the polynomial
// x + 1, together a (0, 2)-sequence in base 2. Dimension 1 through byte
// tables: seven loads instead of a loop over 52 bits.
struct SobolByteTables {
  uint32_t dim1[7][256];
  uint32_t dim1_reversed[7][256];  // the same, each entry's bits reversed
};
extern const SobolByteTables kSobolBytes;

inline uint32_t sobol_bits_dim0(uint64_t index) { return reverse_bits32(uint32_t(index)); }
inline uint32_t sobol_bits_dim1(uint64_t index) {
  uint32_t v = 0;
  for (int b = 0; b < 7 && index != 0; ++b, index >>= 8) v ^= kSobolBytes.dim1[b][index & 0xFF];
  return v;
}
// reverse_bits32(sobol_bits_dim1(index)): reversal commutes with xor.
inline uint32_t sobol_bits_dim1_reversed(uint64_t index) {
  uint32_t v = 0;
  for (int b = 0; b < 7 && index != 0; ++b, index >>= 8) v ^= kSobolBytes.dim1_reversed[b][index & 0xFF];
  return v;
}

}  // namespace lantern
