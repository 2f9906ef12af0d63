// Guided distances in homogeneous media (docs/guiding.md, "Distances in
// media").
//
// Free flight puts a segment's scattering points where the medium is dense
// (density sigma_t T(t)), not where light is: in thin fog lit by a beam,
// most fall in the dark. The guiding field learns, per spatial leaf, the
// radiance its medium vertices scattered back along their paths per unit
// sigma_s (guiding/sd_tree.h, next-event estimation's share included), and
// along a stretch of homogeneous medium this draws t from the product of
// a transmittance and that radiance, piecewise over the leaves the stretch
// crosses:
//   g(t) = S(leaf at t) exp(-sigma t) / M,
// sigma the mean of the channels' extinction, M the integral over the
// stretch (the product of transmittance and learnt in-scattered radiance
// that Herholz et al. 2019, "Volume Path Guiding Based on Zero-Variance
// Random Walk Theory", sec. 5, guide distances by; here the radiance is one
// number per leaf, with no direction).
//
// Only where a segment scatters changes, not whether: free flight decides
// that (with probability P of scattering in this stretch), then the point
// is free flight's with probability kFreeFlightShare, else g's. So the
// point's density is the one-sample mixture
//   p(t) = a p_ff(t) + (1 - a) P g(t),
// positive wherever free flight's p_ff is (integrator/medium_events.h), and
// the weight T sigma_s / p is unbiased; a segment that passes the stretch
// keeps free flight's probability and weight.
#pragma once

#include <algorithm>
#include <cmath>
#include <vector>

#include "guiding/scatter_field.h"

namespace lantern {

class DistanceGuide {
 public:
  static constexpr float kFreeFlightShare = 0.5f;

  // Lays the guide over the stretch o + t d (d unit length), t in [0, len)
  // (len may be infinite), with extinction sigma. False where nothing was
  // learnt along it: free flight alone.
  bool build(const ScatterField& field, const Vec3& o, const Vec3& d, float len, float sigma) {
    bound_.clear(), level_.clear(), cdf_.assign(1, 0.f);
    sigma_ = std::max(sigma, 0.f);
    float decay = 1.f;  // exp(-sigma (ta - bound_[0])), carried from interval to interval
    field.leaves_along(o, d, 0.f, len, [&](float ta, float tb, uint32_t leaf) {
      if (bound_.empty()) bound_.push_back(ta);
      const float x = -sigma_ * (tb - ta), fall = std::expm1(x);  // exp(x) - 1
      const float level = field.level(leaf) * decay;
      const float mass = level * (flat(tb - ta) ? tb - ta : -fall / sigma_);
      decay *= 1.f + fall;
      bound_.push_back(tb);
      level_.push_back(level);
      cdf_.push_back(cdf_.back() + (std::isfinite(mass) ? mass : 0.f));
    });
    return !level_.empty() && cdf_.back() > 0.f && std::isfinite(cdf_.back());
  }

  // A distance drawn from g with the uniform number u (build returned true).
  float sample(float u) const {
    const float x = u * cdf_.back();
    size_t i = size_t(std::upper_bound(cdf_.begin(), cdf_.end(), x) - cdf_.begin());
    i = std::min(std::max(i, size_t(1)), level_.size()) - 1;
    while (i > 0 && !(cdf_[i + 1] > cdf_[i])) --i;  // (u at the top: the last interval with mass)
    const float mass = cdf_[i + 1] - cdf_[i];
    const float v = std::clamp((x - cdf_[i]) / mass, 0.f, 0x1.fffffep-1f);
    const float width = bound_[i + 1] - bound_[i];
    const float offset = flat(width) ? v * width : -std::log1p(v * std::expm1(-sigma_ * width)) / sigma_;
    return std::clamp(bound_[i] + offset, bound_[i], std::nextafter(bound_[i + 1], bound_[i]));
  }

  // g's density at t (per unit length).
  float pdf(float t) const {
    if (level_.empty() || !(t >= bound_.front() && t < bound_.back())) return 0.f;
    const size_t i =
        std::min(size_t(std::upper_bound(bound_.begin(), bound_.end(), t) - bound_.begin()) - 1, level_.size() - 1);
    const float fall = flat(bound_[i + 1] - bound_[i]) ? 1.f : std::exp(-sigma_ * (t - bound_[i]));
    return level_[i] * fall / cdf_.back();
  }

 private:
  // Whether exp(-sigma x) is taken as constant over an interval of width x.
  bool flat(float width) const { return sigma_ * width < 1e-5f; }

  std::vector<float> bound_;  // the intervals' ends: interval i is [bound_[i], bound_[i + 1])
  std::vector<float> level_;  // S of each interval's leaf times exp(-sigma (its start - bound_[0]))
  std::vector<float> cdf_;    // the intervals' masses, summed up to each bound
  float sigma_ = 0.f;
};

}  // namespace lantern
