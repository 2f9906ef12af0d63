#include "sampler/sampler.h"

#include <algorithm>
#include <stdexcept>

namespace lantern {

namespace {

constexpr int kTimeBudgetLog2Block = 16;

}  // namespace

Randomization parse_randomization(const std::string& n) {
  if (n == "none") return Randomization::None;
  if (n == "permutedigits") return Randomization::PermuteDigits;
  if (n == "fastowen") return Randomization::FastOwen;
  if (n == "owen") return Randomization::Owen;
  throw std::invalid_argument("unknown randomization \"" + n + "\" (expected fastowen, owen, permutedigits or none)");
}

Randomization default_randomization(SamplerKind k) {
  if (k == SamplerKind::Halton) return Randomization::PermuteDigits;
  if (k == SamplerKind::Independent || k == SamplerKind::Stratified) return Randomization::None;
  return Randomization::FastOwen;
}

const char* randomization_name(Randomization r) {
  switch (r) {
    case Randomization::None: return "none";
    case Randomization::PermuteDigits: return "permutedigits";
    case Randomization::FastOwen: return "fastowen";
    case Randomization::Owen: return "owen";
  }
  return "?";
}

PathSampler PathSampler::metropolis(MetropolisSampler* chain) {
  static const SamplerSpec spec = [] {
    SamplerSpec s;
    s.metropolis = true;
    return s;
  }();
  return PathSampler{&spec, uint64_t(reinterpret_cast<uintptr_t>(chain)), 0, 0};
}

SamplerSpec make_sampler_spec(const SamplerSettings& st, int width, int height, uint32_t planned_spp, uint64_t seed) {
  SamplerSpec s;
  s.kind = st.type;
  s.randomize = st.randomization.empty() ? default_randomization(s.kind) : parse_randomization(st.randomization);
  s.seed = mix64(seed ^ mix64(st.seed + 0x2545F4914F6CDD1DULL));
  s.width = uint32_t(std::max(width, 1));
  s.log2_spp = planned_spp > 0 ? ceil_log2(planned_spp) : kTimeBudgetLog2Block;
  const int res_bits = ceil_log2(uint64_t(std::max({width, height, 1})));
  s.index_bits = 2 * res_bits + s.log2_spp;
  s.xsamples = uint32_t(std::max(st.xsamples, 1));
  s.ysamples = uint32_t(std::max(st.ysamples, 1));
  s.jitter = st.jitter;
  if (s.kind == SamplerKind::Halton) s.halton = make_halton_layout(width, height);
  if (s.kind == SamplerKind::Sobol) s.sobol = make_sobol_layout(width, height);
  return s;
}

PathSampler PathSampler::make(const SamplerSpec& s, uint32_t pixel, uint64_t sample_index) {
  PathSampler p;
  p.spec = &s;
  const uint32_t x = pixel % s.width, y = pixel / s.width;
  const uint64_t block_mask = (uint64_t(1) << s.log2_spp) - 1;
  switch (s.kind) {
    case SamplerKind::Independent:
      p.key = hash_key(s.seed, pixel, sample_index);
      break;
    case SamplerKind::ZSobol:
      p.key = (morton_2d(x, y) << s.log2_spp) | (sample_index & block_mask);
      p.salt = hash_combine(s.seed, sample_index >> s.log2_spp);
      break;
    case SamplerKind::PaddedSobol:
      p.index = uint32_t(sample_index & block_mask);
      p.salt = hash_combine(s.seed, pixel, sample_index >> s.log2_spp);
      break;
    case SamplerKind::Stratified: {
      const uint64_t n = uint64_t(s.xsamples) * s.ysamples;
      p.index = uint32_t(sample_index % n);
      p.salt = hash_combine(s.seed, pixel, sample_index / n);
      break;
    }
    case SamplerKind::Halton:
      p.key = halton_index(s.halton, x, y, sample_index);
      p.salt = hash_combine(s.seed, pixel);
      break;
    case SamplerKind::Sobol:
      p.key = sobol_index(s.sobol, x, y, sample_index);
      p.salt = hash_combine(s.seed, pixel);
      break;
  }
  return p;
}

}  // namespace lantern
