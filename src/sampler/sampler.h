// The per-path sampler: every value is a pure function of (seed, pixel,
// sample index, dimension), whatever the kind, so an image does not depend
// on how the work is scheduled over threads, and a checkpoint resumes
// exactly. Kinds and randomisations are pbrt-v4's (docs/samplers.md);
// dimensions are assigned by sampler/dimensions.h.
#pragma once

#include <cstdint>
#include <string>

#include "lantern/scene.h"
#include "math/common.h"
#include "sampler/global_sobol.h"
#include "sampler/halton.h"
#include "sampler/metropolis_sampler.h"
#include "sampler/padded_sobol.h"
#include "sampler/sobol_matrices.h"
#include "sampler/stratified.h"
#include "sampler/zsobol.h"

namespace lantern {


// Everything a render's samples depend on besides pixel, index, dimension.
struct SamplerSpec {
  SamplerKind kind = SamplerKind::Independent;
  Randomization randomize = Randomization::None;
  uint64_t seed = 0;
  uint32_t width = 1;
  int log2_spp = 0;      // zsobol, paddedsobol: bits of a pixel's block of indices
  int index_bits = 0;    // zsobol: of the Morton index and the sample index
  bool open_count = false;  // planned for a time budget: how many samples a pixel gets is not known
  // zsobol laid out pass-major (make_light_start_spec): the bits of the
  // linear pixel index, below the sample index's; 0 for the usual layout.
  int pixel_bits = 0;
  uint32_t xsamples = 1, ysamples = 1;  // stratified
  bool jitter = true;
  HaltonLayout halton;
  SobolLayout sobol;
  // Metropolis (integrator/metropolis.h): each path's numbers are its
  // chain's proposal, PathSampler::key pointing at the chain's sampler.
  bool metropolis = false;
};

// The samples per pixel a render plans (its --spp), or 0 under a time
// budget: the per-pixel block is then 2^16 (a render past that many
// samples per pixel continues with a freshly randomised block).
SamplerSpec make_sampler_spec(const SamplerSettings& s, int width, int height, uint32_t planned_spp, uint64_t seed);
// The layout of the light subpath's first point (bdpt, lt, vcm): the eye
// spec itself, unless it is zsobol under an open count. There each pixel's
// block of 2^16 samples stratifies its own light points but not the
// image's, and light tracing splats the points of all pixels' light
// subpaths onto the same pixels. So the points are laid out pass-major,
// in groups of four passes: the k-th four samples of every pixel are one
// aligned block of the sequence, the image's points of each group, and of
// the first 2^k groups, stratified together (exact nets when width x height is a power of two, unions of nets otherwise) (docs/light-sampling.md).
SamplerSpec make_light_start_spec(const SamplerSpec& eye, int width, int height);
// Throws std::invalid_argument naming the valid choices.
Randomization parse_randomization(const std::string& name);
// pbrt-v4's: permutedigits for halton, fastowen for the Sobol samplers.
Randomization default_randomization(SamplerKind k);
const char* randomization_name(Randomization r);

struct PathSampler {
  const SamplerSpec* spec = nullptr;
  uint64_t key = 0;   // the kind's per-sample key: a hash, a global index, zsobol's bits reversed, ...
  uint64_t salt = 0;  // per pixel (and round of blocks) randomisation seed
  uint32_t index = 0;  // sample index within the pixel's block

  static PathSampler make(const SamplerSpec& spec, uint32_t pixel, uint64_t sample_index);
  // The numbers of a Markov chain's current proposal (sampler/metropolis_sampler.h).
  static PathSampler metropolis(MetropolisSampler* chain);
  float get1d(uint32_t dimension) const;
  Vec2 get2d(uint32_t dimension) const;
};

// A dimension's own hash of the sample's salt: its randomisation seeds.
inline uint64_t dimension_hash(uint64_t salt, uint32_t d) { return mix64(salt ^ (uint64_t(d) * 0x9E3779B97F4A7C15ULL)); }

// Scrambled Sobol values of a permuted index: dimension 0 for 1D, 0 and 1
// for 2D (zsobol and paddedsobol; h is the dimension's hash).
inline float sobol_1d(uint64_t i, Randomization r, uint64_t h) {
  return bits32_to_unit_float(scrambled_van_der_corput(i, r, uint32_t(h >> 32)));
}
inline Vec2 sobol_2d(uint64_t i, Randomization r, uint64_t h) {
  const uint64_t h2 = mix64(h);
  // (fastowen reverses dimension 1's bits before its hash: the table of
  // reversed columns gives them so)
  const uint32_t y = r == Randomization::FastOwen
                         ? reverse_bits32(laine_karras_hash(sobol_bits_dim1_reversed(i), uint32_t(h2 >> 32)))
                         : scramble_bits(sobol_bits_dim1(i), r, uint32_t(h2 >> 32));
  return Vec2(bits32_to_unit_float(scrambled_van_der_corput(i, r, uint32_t(h2))), bits32_to_unit_float(y));
}

inline float PathSampler::get1d(uint32_t d) const {
  const SamplerSpec& s = *spec;
  // (the chain's numbers change only between iterations: its sampler is
  // not part of this value, which stays a read-only handle)
  if (s.metropolis) [[unlikely]]
    return reinterpret_cast<MetropolisSampler*>(key)->get(d);
  switch (s.kind) {
    case SamplerKind::Independent:
      return bits_to_unit_float(mix64(key ^ (uint64_t(d) * 0x9E3779B97F4A7C15ULL)));
    case SamplerKind::ZSobol: {
      const uint64_t h = dimension_hash(salt, d);
      return sobol_1d(zsobol_permuted_index(key, s.index_bits, h), s.randomize, h);
    }
    case SamplerKind::PaddedSobol: {
      const uint64_t h = dimension_hash(salt, d);
      return sobol_1d(padded_sobol_index(index, s.log2_spp, h), s.randomize, h);
    }
    case SamplerKind::Stratified:
      return stratified_1d(index, s.xsamples * s.ysamples, s.jitter, dimension_hash(salt, d));
    case SamplerKind::Halton:
      if (d < 2) return halton_film(s.halton, key, int(d), s.randomize, salt);
      return halton_sample(key, int(d), s.randomize, salt);  // per pixel, as for sobol
    case SamplerKind::Sobol: {
      if (d < 2) return sobol_film(s.sobol, key, int(d), s.randomize, uint32_t(mix64(salt + d)));
      // Scrambled per pixel as well as per dimension: a pixel's samples are
      // a subsequence that the film dimensions pick, and neighbouring
      // pixels' subsequences are alike; one scramble for all would show
      // that likeness as a pattern in the image.
      const int dim = int(2 + (d - 2) % uint32_t(kSobolDimensions - 2));
      const uint32_t seed = uint32_t(dimension_hash(salt, uint32_t(dim)));
      return bits32_to_unit_float(scramble_bits(sobol_bits(key, dim), s.randomize, seed));
    }
  }
  return 0.f;
}

inline Vec2 PathSampler::get2d(uint32_t d) const {
  const SamplerSpec& s = *spec;
  switch (s.kind) {
    case SamplerKind::ZSobol: {
      const uint64_t h = dimension_hash(salt, d);
      return sobol_2d(zsobol_permuted_index(key, s.index_bits, h), s.randomize, h);
    }
    case SamplerKind::PaddedSobol: {
      const uint64_t h = dimension_hash(salt, d);
      return sobol_2d(padded_sobol_index(index, s.log2_spp, h), s.randomize, h);
    }
    case SamplerKind::Stratified:
      return stratified_2d(index, s.xsamples, s.ysamples, s.jitter, dimension_hash(salt, d));
    default:
      return Vec2(get1d(d), get1d(d + 1));
  }
}

}  // namespace lantern
