// Piecewise-constant 1D and 2D distributions, sampled by inverting their CDF.
// Used for light selection by power and for environment map sampling.
#pragma once

#include <vector>

#include "math/common.h"

namespace lantern {

class Distribution1D {
 public:
  Distribution1D() = default;
  explicit Distribution1D(std::vector<float> weights);

  size_t size() const { return func_.size(); }
  float integral() const { return integral_; }
  // Continuous sample in [0, 1); pdf is with respect to that interval.
  float sample_continuous(float u, float* pdf, size_t* offset) const;
  // Discrete sample; pmf of the chosen index. u_remapped (optional): where
  // u lies within the chosen index's share of [0, 1), rescaled to [0, 1),
  // which is uniform again given the choice (reusing it keeps a
  // stratified u stratified; light_choice.h says when that pays).
  size_t sample_discrete(float u, float* pmf, float* u_remapped = nullptr) const;
  float discrete_pmf(size_t i) const {
    return integral_ > 0.f ? func_[i] / (integral_ * float(func_.size())) : 0.f;
  }
  float func(size_t i) const { return func_[i]; }

 private:
  size_t find_interval(float u) const;
  std::vector<float> func_;
  std::vector<float> cdf_;
  float integral_ = 0.f;
};

class Distribution2D {
 public:
  Distribution2D() = default;
  // weights in row-major order, nv rows of nu values.
  Distribution2D(const std::vector<float>& weights, int nu, int nv);

  Vec2 sample_continuous(Vec2 u, float* pdf) const;
  float pdf(Vec2 p) const;
  bool empty() const { return conditional_.empty(); }

 private:
  std::vector<Distribution1D> conditional_;
  Distribution1D marginal_;
};

}  // namespace lantern
