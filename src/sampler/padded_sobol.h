// pbrt-v4's paddedsobol: each pixel draws its own 2D Sobol (0, 2)-sequence,
// and each dimension visits it in its own random order, so dimensions are
// decorrelated ("padding", Kollig & Keller 2002). The order is a random
// hierarchical one (sampler/nested_scramble.h), so that the first 2^k
// samples in any order are one aligned block of the sequence: stratified
// whatever the count.
#pragma once

#include <cstdint>

#include "sampler/nested_scramble.h"

namespace lantern {

inline uint64_t padded_sobol_index(uint64_t index, int log2_spp, uint64_t dim_hash) {
  return nested_scramble_index(index, log2_spp, dim_hash);
}

}  // namespace lantern
