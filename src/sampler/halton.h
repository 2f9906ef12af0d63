// pbrt-v4's halton sampler: one Halton sequence over the whole image. The
// first two dimensions (bases 2 and 3) place the sample on the film; the
// image is tiled by 2^j x 3^k pixel blocks (at most 128 pixels a side) and
// the index of a pixel's i-th sample is found with the Chinese remainder
// theorem (Grünschloß, Raab & Keller 2012, "Enumerating quasi-Monte Carlo
// point sequences in elementary intervals"). Dimension d >= 2 uses the d-th
// prime, with random digit permutations (Faure & Tezuka) or Owen scrambling.
#pragma once

#include <cstdint>

#include "sampler/scramble.h"

namespace lantern {

struct HaltonLayout {
  uint32_t scale[2] = {1, 1};  // 2^j and 3^k
  int exponent[2] = {0, 0};
  uint64_t stride = 1;  // scale[0] * scale[1]
  uint64_t mult_inverse[2] = {0, 0};
};

inline constexpr int kHaltonDimensions = 1000;  // primes available; later dimensions wrap to 2

HaltonLayout make_halton_layout(int width, int height);
uint64_t halton_index(const HaltonLayout& h, uint32_t x, uint32_t y, uint64_t sample_index);
// The offset of the sample inside its pixel, axis 0 or 1: the digits
// after the pixel's, randomised as the other dimensions are.
float halton_film(const HaltonLayout& h, uint64_t index, int axis, Randomization r, uint64_t seed);
float halton_sample(uint64_t index, int dimension, Randomization r, uint64_t seed);

}  // namespace lantern
