// pbrt-v4's Gaussian pixel filter, per axis g(x) - g(r) on [-r, r] (the
// normal density less its value at the radius, so the filter reaches zero
// there), drawn exactly from a piecewise-linear table of it. Sampling and
// the density light-tracing splats are weighted by use the same table, so
// they agree to rounding; the table (segments of at most sigma / 24, from
// 64 to 512 a side) departs from the filter by less than 3e-4 of its peak
// (tested), and a lookup costs a binary search and a square root instead
// of the three erf calls of inverting the normal's CDF.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>

namespace lantern {

class GaussianFilterTable {
 public:
  static constexpr int kMaxSegments = 512;

  GaussianFilterTable() : GaussianFilterTable(1.5f, 0.5f) {}
  GaussianFilterTable(float radius, float sigma)
      : n_(std::clamp(int(std::ceil(24.0 * double(radius) / double(sigma))), 64, kMaxSegments)),
        radius_(radius),
        h_(radius / float(n_)) {
    const auto g = [sigma](double x) { return std::exp(-x * x / (2.0 * double(sigma) * sigma)); };
    const double edge = g(double(radius));
    double area = 0.0;
    cdf_[0] = 0.f;
    for (int k = 0; k <= n_; ++k) {
      v_[size_t(k)] = float(std::max(0.0, g(double(k) * h_) - edge));
      if (k > 0) {
        area += 0.5 * h_ * (double(v_[size_t(k - 1)]) + v_[size_t(k)]);
        cdf_[size_t(k)] = float(area);
      }
    }
    v_[size_t(n_)] = 0.f;
    total_ = float(area);
  }

  // Offset in [-radius, radius] for u in [0, 1), increasing in u.
  float sample(float u) const {
    const float t = 2.f * u - 1.f;
    const float x = sample_half(std::fabs(t));
    return t < 0.f ? -x : x;
  }

  // Density of sample()'s offsets.
  float density(float x) const {
    const float a = std::fabs(x) / h_;
    if (!(a < float(n_))) return 0.f;
    const int k = std::min(int(a), n_ - 1);
    const float s = a - float(k);
    const float v = v_[size_t(k)] + (v_[size_t(k + 1)] - v_[size_t(k)]) * s;
    return v / (2.f * total_);
  }

 private:
  // x in [0, radius] with density proportional to the table.
  float sample_half(float t) const {
    const float target = std::min(t, 1.f) * total_;
    int k = int(std::upper_bound(cdf_.begin(), cdf_.begin() + n_ + 1, target) - cdf_.begin()) - 1;
    k = std::clamp(k, 0, n_ - 1);
    // Within the segment the density is linear, v_k + (v_k+1 - v_k) s: solve
    // h (v_k s + (v_k+1 - v_k) s^2 / 2) = area for s, in the form that
    // does not cancel.
    const float area = std::max(target - cdf_[size_t(k)], 0.f) / h_;
    const float b = v_[size_t(k)], d = v_[size_t(k + 1)] - v_[size_t(k)];
    const float disc = std::max(b * b + 2.f * d * area, 0.f);
    const float denom = b + std::sqrt(disc);
    const float s = denom > 0.f ? std::clamp(2.f * area / denom, 0.f, 1.f) : 0.f;
    return std::min((float(k) + s) * h_, radius_);
  }

  int n_;  // segments over [0, radius]
  float radius_, h_;
  float total_ = 1.f;  // the table's area over [0, radius]
  std::array<float, kMaxSegments + 1> v_{}, cdf_{};
};

}  // namespace lantern
