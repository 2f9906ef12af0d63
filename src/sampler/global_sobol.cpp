#include "sampler/global_sobol.h"

#include <stdexcept>

#include "sampler/sobol_matrices.h"

namespace lantern {

namespace {

// The target bits of the low index bits l: the top m bits of dimension 0 in
// bits [0, m), those of dimension 1 in bits [m, 2m).
uint32_t target_bits(uint64_t l, int m) {
  if (m == 0) return 0;
  return (sobol_bits_dim0(l) >> (32 - m)) | ((sobol_bits_dim1(l) >> (32 - m)) << m);
}

}  // namespace

SobolLayout make_sobol_layout(int width, int height) {
  SobolLayout s;
  s.log2_scale = ceil_log2(uint64_t(std::max(width, height)));
  const int m = s.log2_scale, n = 2 * m;
  // Gauss-Jordan elimination over GF(2) on [A | I], A's column k the
  // target of index bit k; the rows are kept as bit masks.
  uint64_t rows[32];
  for (int r = 0; r < n; ++r) {
    uint64_t a = 0;
    for (int k = 0; k < n; ++k) a |= uint64_t((target_bits(uint64_t(1) << k, m) >> r) & 1u) << k;
    rows[r] = a | (uint64_t(1) << (32 + r));
  }
  for (int c = 0; c < n; ++c) {
    int pivot = c;
    while (pivot < n && !((rows[pivot] >> c) & 1)) ++pivot;
    if (pivot == n) throw std::logic_error("Sobol dimensions 0 and 1 are not a (0, 2)-sequence");
    std::swap(rows[c], rows[pivot]);
    for (int r = 0; r < n; ++r)
      if (r != c && ((rows[r] >> c) & 1)) rows[r] ^= rows[c];
  }
  // Row r of the inverse says which target bits make up index bit r.
  for (int b = 0; b < n; ++b) {
    uint32_t col = 0;
    for (int r = 0; r < n; ++r) col |= uint32_t((rows[r] >> (32 + b)) & 1u) << r;
    s.inverse[b] = col;
  }
  return s;
}

uint64_t sobol_index(const SobolLayout& s, uint32_t x, uint32_t y, uint64_t sample_index) {
  const int m = s.log2_scale;
  const uint64_t high = sample_index << (2 * m);
  const uint32_t target = (x | (y << m)) ^ target_bits(high, m);
  uint64_t low = 0;
  for (int b = 0; b < 2 * m; ++b)
    if ((target >> b) & 1) low ^= s.inverse[b];
  return high | low;
}

float sobol_film(const SobolLayout& s, uint64_t index, int axis, Randomization r, uint32_t seed) {
  uint32_t v = axis == 0 ? sobol_bits_dim0(index) : sobol_bits_dim1(index);
  return bits32_to_unit_float(scramble_bits(s.log2_scale >= 32 ? 0u : v << s.log2_scale, r, seed));
}

}  // namespace lantern
