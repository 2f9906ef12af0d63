// Guided distances in homogeneous media (docs/guiding.md, "Distances in
// media").
//
// Free flight puts a segment's scattering points where the medium is dense
// (density sigma_t T(t)), not where light is: in thin fog lit by a beam,
// most fall in the dark. The guiding field learns, per spatial leaf, the
// radiance its medium vertices scattered back along their paths per unit
// sigma_s (guiding/scatter_field.h, next-event estimation's share included), and
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
    bound_.clear(), span_.clear(), cdf_.assign(1, 0.0);
    sigma_ = std::max(sigma, 0.f);
    double decay = 1.0;  // exp(-sigma (ta - bound_[0])), carried from interval to interval
    bool finite = true;
    field.leaves_along(o, d, 0.f, len, [&](float ta, float tb, uint32_t leaf) {
      if (bound_.empty()) bound_.push_back(ta);
      const float x = -sigma_ * (tb - ta), fall = std::expm1(x);  // exp(x) - 1
      const float span = flat(tb - ta) ? tb - ta : -fall / sigma_;  // the integral of exp(-sigma s) over it
      const double mass = double(field.level(leaf)) * decay * double(span);
      finite = finite && std::isfinite(mass);
      decay *= 1.0 + double(fall);
      bound_.push_back(tb);
      span_.push_back(span);
      cdf_.push_back(cdf_.back() + mass);
    });
    return !span_.empty() && finite && cdf_.back() > 0.0 && std::isfinite(cdf_.back());
  }

  // A distance drawn from g with the uniform number u (build returned true).
  float sample(float u) const {
    const double x = double(u) * cdf_.back();
    size_t i = size_t(std::upper_bound(cdf_.begin(), cdf_.end(), x) - cdf_.begin());
    i = std::min(std::max(i, size_t(1)), span_.size()) - 1;
    while (i > 0 && !(cdf_[i + 1] > cdf_[i])) --i;  // (u at the top: the last interval with mass)
    const float v = std::clamp(float((x - cdf_[i]) / (cdf_[i + 1] - cdf_[i])), 0.f, 0x1.fffffep-1f);
    const float width = bound_[i + 1] - bound_[i];
    const float offset = flat(width) ? v * width : -std::log1p(v * std::expm1(-sigma_ * width)) / sigma_;
    return std::clamp(bound_[i] + offset, bound_[i], std::nextafter(bound_[i + 1], bound_[i]));
  }

  // g's density at t (per unit length): its interval's share of the mass,
  // spread within it as sample spreads it.
  float pdf(float t) const {
    if (span_.empty() || !(t >= bound_.front() && t < bound_.back())) return 0.f;
    const size_t i =
        std::min(size_t(std::upper_bound(bound_.begin(), bound_.end(), t) - bound_.begin()) - 1, span_.size() - 1);
    const float within = flat(bound_[i + 1] - bound_[i]) ? 1.f : std::exp(-sigma_ * (t - bound_[i]));
    return float((cdf_[i + 1] - cdf_[i]) / cdf_.back()) * within / span_[i];
  }

 private:
  // Whether exp(-sigma x) is taken as constant over an interval of width x.
  bool flat(float width) const { return sigma_ * width < 1e-5f; }

  std::vector<float> bound_;  // the intervals' ends: interval i is [bound_[i], bound_[i + 1])
  std::vector<float> span_;   // the integral of exp(-sigma (t - its start)) over each
  std::vector<double> cdf_;   // the intervals' masses, summed up to each bound
  float sigma_ = 0.f;
};

}  // namespace lantern
