// pbrt-v4's sobol sampler: one Sobol sequence over the whole image. Its
// first two dimensions, scaled by the image's power-of-two size, place the
// sample on the film; the index of a pixel's i-th sample is i followed by
// the 2m low bits that put dimensions 0 and 1 in the pixel, found by
// inverting the 2m x 2m binary matrix of those bits (Grünschloß, Raab &
// Keller 2012). Later dimensions use Joe & Kuo's matrices, scrambled.
#pragma once

#include <cstdint>

#include "sampler/scramble.h"

namespace lantern {

struct SobolLayout {
  int log2_scale = 0;        // m: the image fits in 2^m x 2^m pixels
  uint32_t inverse[32] = {};  // column b: the low index bits that set bit b of the target
};

SobolLayout make_sobol_layout(int width, int height);
uint64_t sobol_index(const SobolLayout& s, uint32_t x, uint32_t y, uint64_t sample_index);
// The offset of the sample inside its pixel, axis 0 or 1: the bits below
// the pixel's, randomised as the other dimensions are (a nested scramble
// keeps the offsets stratified in the pixel and makes each uniform in it,
// so an ensemble of seeds averages the pixel filter without bias).
float sobol_film(const SobolLayout& s, uint64_t index, int axis, Randomization r, uint32_t seed);

}  // namespace lantern
