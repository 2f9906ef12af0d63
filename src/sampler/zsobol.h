// pbrt-v4's default sampler (Ahmed & Wonka 2020, "Screen-space blue-noise
// diffusion of Monte Carlo sampling error via hierarchical ordering of
// pixels"): one global Sobol (0, 2)-sequence, pixels laid along it in Morton
// order, each pixel taking a block of 2^log2_spp consecutive indices. Before
// a dimension uses the index, the index is permuted hierarchically, at
// random per dimension (sampler/nested_scramble.h): every dimension sees
// the pixels' blocks shuffled but never split, so the first 4^k samples of
// a pixel stay stratified, and neighbouring pixels share larger aligned
// blocks (error distributed as blue noise).
//
// Ahmed & Wonka, and pbrt-v4, permute base-4 digits with any of the 24
// permutations, one hash per digit; Lantern flips base-2 digits, one hash
// per index (a subset of those permutations with the same block property):
// 3x cheaper per sample (docs/performance.md).
#pragma once

#include <cstdint>

#include "sampler/nested_scramble.h"

namespace lantern {

// key = (Morton index << log2_spp) | sample index, index_bits wide, given
// with its bits reversed (reverse_bits64(key): PathSampler::make).
inline uint64_t zsobol_permuted_index(uint64_t reversed_key, int index_bits, uint64_t dim_hash) {
  return nested_scramble_reversed_index(reversed_key, index_bits, dim_hash);
}

}  // namespace lantern
