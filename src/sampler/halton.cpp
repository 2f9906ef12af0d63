#include "sampler/halton.h"

#include <vector>

#include "math/common.h"
#include "sampler/permutation.h"

namespace lantern {

namespace {

std::vector<uint32_t> first_primes(int count) {
  std::vector<uint32_t> primes;
  for (uint32_t n = 2; int(primes.size()) < count; ++n) {
    bool prime = true;
    for (uint32_t p : primes) {
      if (p * p > n) break;
      if (n % p == 0) {
        prime = false;
        break;
      }
    }
    if (prime) primes.push_back(n);
  }
  return primes;
}

const std::vector<uint32_t>& primes() {
  static const std::vector<uint32_t> p = first_primes(kHaltonDimensions);
  return p;
}

// The digits of a, reversed about the radix point.
double radical_inverse(uint64_t a, uint32_t base) {
  const double inv = 1.0 / base;
  double f = inv, sum = 0.0;
  for (; a != 0; a /= base, f *= inv) sum += double(a % base) * f;
  return sum;
}

// Inverse of the first `digits` digits' reversal: the integer whose
// radical inverse, scaled by base^digits, is `value`.
uint64_t inverse_radical_inverse(uint64_t value, uint32_t base, int digits) {
  uint64_t r = 0;
  for (int i = 0; i < digits; ++i, value /= base) r = r * base + value % base;
  return r;
}

// x^-1 mod m by the extended Euclidean algorithm (gcd(x, m) = 1).
uint64_t inverse_mod(uint64_t x, uint64_t m) {
  int64_t t = 0, new_t = 1, r = int64_t(m), new_r = int64_t(x % m);
  while (new_r != 0) {
    int64_t q = r / new_r;
    int64_t tmp = t - q * new_t;
    t = new_t;
    new_t = tmp;
    tmp = r - q * new_r;
    r = new_r;
    new_r = tmp;
  }
  return uint64_t(t < 0 ? t + int64_t(m) : t) % m;
}

}  // namespace

HaltonLayout make_halton_layout(int width, int height) {
  HaltonLayout h;
  const int res[2] = {width, height};
  for (int i = 0; i < 2; ++i) {
    const uint32_t base = i == 0 ? 2 : 3;
    while (h.scale[i] < uint32_t(std::min(res[i], 128))) {
      h.scale[i] *= base;
      ++h.exponent[i];
    }
  }
  h.stride = uint64_t(h.scale[0]) * h.scale[1];
  h.mult_inverse[0] = h.scale[0] > 1 ? inverse_mod(h.scale[1], h.scale[0]) : 0;
  h.mult_inverse[1] = h.scale[1] > 1 ? inverse_mod(h.scale[0], h.scale[1]) : 0;
  return h;
}

// The index i of the sequence whose first exponent[0] base-2 digits and
// exponent[1] base-3 digits, reversed, are the pixel's coordinates within
// its block: i mod 2^j and i mod 3^k are fixed, and the Chinese remainder
// theorem gives i mod stride; sample_index counts the indices that qualify.
uint64_t halton_index(const HaltonLayout& h, uint32_t x, uint32_t y, uint64_t sample_index) {
  const uint32_t p[2] = {x % 128u, y % 128u};
  uint64_t index = 0;
  for (int i = 0; i < 2; ++i) {
    if (h.scale[i] <= 1) continue;
    const uint64_t offset = inverse_radical_inverse(p[i], i == 0 ? 2 : 3, h.exponent[i]);
    index += offset * (h.stride / h.scale[i]) % h.stride * h.mult_inverse[i];
  }
  return index % h.stride + sample_index * h.stride;
}

float halton_film(const HaltonLayout& h, uint64_t index, int axis, Randomization r, uint64_t seed) {
  return halton_sample(index / h.scale[axis], axis, r, seed);  // dimensions 0 and 1: bases 2 and 3
}

// Digit j (least significant first) becomes the (j+1)-th digit after the
// radix point, through a permutation of its own: per digit position for
// permutedigits, per position and all lower digits for owen. Digits past
// the last non-zero one are zeros that the permutations still move, so the
// loop runs until a digit no longer changes a float.
float halton_sample(uint64_t index, int dimension, Randomization r, uint64_t seed) {
  const uint32_t base = primes()[size_t(dimension % kHaltonDimensions)];
  if (r == Randomization::None) return min_num(float(radical_inverse(index, base)), kOneMinusEpsilon);
  const uint64_t dim_seed = hash_combine(seed, uint64_t(dimension));
  // In base 2 the radical inverse is the reversed bits, and the digit
  // randomisations are the Sobol samplers' (one hash, not one per digit).
  if (base == 2) return bits32_to_unit_float(scramble_bits(reverse_bits32(uint32_t(index)), r, uint32_t(dim_seed)));
  // fastowen is a base-2 construction; in other bases it means full Owen.
  const bool owen = r == Randomization::Owen || r == Randomization::FastOwen;
  const double inv = 1.0 / base;
  double f = inv, sum = 0.0;
  uint64_t lower = 0;
  for (uint64_t j = 0; f > 0x1p-26; ++j, f *= inv) {
    const uint32_t digit = uint32_t(index % base);
    index /= base;
    const uint64_t s = dim_seed ^ (j * 0x9E3779B97F4A7C15ULL) ^ (owen ? lower * 0xD1B54A32D192ED03ULL : 0);
    sum += double(permutation_element(digit, base, s)) * f;
    lower = lower * base + digit + 1;  // + 1: a prefix of zeros differs from none
  }
  return min_num(float(sum), kOneMinusEpsilon);
}

}  // namespace lantern
