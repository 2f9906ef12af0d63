#include "sampler/sobol_matrices.h"

#include <boost/random/detail/sobol_table.hpp>
#include <vector>

namespace lantern {

namespace {

using JoeKuo = boost::random::detail::qrng_tables::sobol;

// Direction numbers m_k (odd, below 2^k) by the recurrence of Bratley & Fox
// (1988): for the primitive polynomial x^s + a_1 x^(s-1) + ... + a_(s-1) x + 1,
// m_k = 2 a_1 m_(k-1) ^ 4 a_2 m_(k-2) ^ ... ^ 2^s m_(k-s) ^ m_(k-s).
// Column k (0-based) of the matrix is m_(k+1) / 2^(k+1) as a 32-bit fraction.
void fill_dimension(int d, uint32_t* columns) {
  uint64_t m[kSobolColumns + 1] = {};
  if (d == 0) {
    for (int k = 1; k <= kSobolColumns; ++k) m[k] = 1;
  } else {
    const unsigned poly = JoeKuo::polynomial(size_t(d - 1));
    int s = 0;
    while ((poly >> (s + 1)) != 0) ++s;
    for (int k = 1; k <= s && k <= kSobolColumns; ++k) m[k] = JoeKuo::minit(size_t(d - 1), size_t(k - 1));
    for (int k = s + 1; k <= kSobolColumns; ++k) {
      uint64_t v = m[k - s] ^ (m[k - s] << s);
      for (int i = 1; i < s; ++i)
        if ((poly >> (s - i)) & 1) v ^= m[k - i] << i;
      m[k] = v;
    }
  }
  for (int k = 1; k <= kSobolColumns; ++k)
    columns[k - 1] = k <= 32 ? uint32_t(m[k] << (32 - k)) : uint32_t(m[k] >> (k - 32));
}

std::vector<uint32_t> build_all() {
  std::vector<uint32_t> all(size_t(kSobolDimensions) * kSobolColumns);
  for (int d = 0; d < kSobolDimensions; ++d) fill_dimension(d, &all[size_t(d) * kSobolColumns]);
  return all;
}

SobolByteTables build_bytes() {
  uint32_t columns[kSobolColumns];
  fill_dimension(1, columns);
  SobolByteTables t{};
  for (int b = 0; b < 7; ++b)
    for (uint32_t byte = 0; byte < 256; ++byte) {
      uint32_t v = 0;
      for (int bit = 0; bit < 8; ++bit)
        if ((byte >> bit) & 1 && b * 8 + bit < kSobolColumns) v ^= columns[b * 8 + bit];
      t.dim1[b][byte] = v;
      t.dim1_reversed[b][byte] = reverse_bits32(v);
    }
  return t;
}

}  // namespace

const SobolByteTables kSobolBytes = build_bytes();

const uint32_t* sobol_matrix(int dimension) {
  static const std::vector<uint32_t> all = build_all();
  return &all[size_t(dimension % kSobolDimensions) * kSobolColumns];
}

}  // namespace lantern
