// Pixel filters with negative lobes (pbrt-v4's "mitchell" and "sinc"), per
// axis. A camera sample's offset is drawn with density q proportional to
// |f| (a piecewise-linear table of it) and carries the sign s of f there;
// the film divides each pixel's signed sum by its signed count (Film), so
// that a pixel estimates the integral of g L, g = s q / Z with Z the
// integral of s q: pbrt-v4's ratio estimator, sum of w L over sum of w,
// whose weights w = f / pdf are here one magnitude with a sign. Light-
// tracing splats are weighted by the same g (weight()), so both kinds of
// estimate see one filter. The table has 1024 segments a side: g departs
// from f / (integral of f) only within the segments where f changes sign,
// each 1/512 of the radius wide.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>

namespace lantern {

class SignedFilterTable {
 public:
  static constexpr int kSegments = 1024;

  struct Sample {
    float x;
    bool negative;
  };

  SignedFilterTable() = default;
  // f: the filter's even profile, evaluated on [0, radius].
  template <class F>
  SignedFilterTable(float radius, F&& f) : radius_(radius), h_(radius / float(kSegments)) {
    for (int k = 0; k <= kSegments; ++k) f_[size_t(k)] = float(f(double(k) * double(h_)));
    double area = 0.0, signed_area = 0.0;
    cdf_[0] = 0.f;
    for (int k = 0; k < kSegments; ++k) {
      const double a = std::fabs(double(f_[size_t(k)])), b = std::fabs(double(f_[size_t(k + 1)]));
      area += 0.5 * double(h_) * (a + b);
      cdf_[size_t(k + 1)] = float(area);
      // The signed integral of q over the segment, by its sign's own rule
      // (sign of the interpolated f), 16 midpoints: exact where the sign
      // does not change.
      for (int j = 0; j < 16; ++j) {
        const double t = (double(j) + 0.5) / 16.0;
        signed_area += (sign_at(k, float(t)) ? -1.0 : 1.0) * (a + (b - a) * t) * double(h_) / 16.0;
      }
    }
    total_ = float(area);
    normalisation_ = float(area / signed_area);  // 1 / Z, with q = |table| / area (not finite: invalid)
  }

  // Offset in [-radius, radius] and the sign of the filter there, for u in
  // [0, 1).
  Sample sample(float u) const {
    const float t = 2.f * u - 1.f;
    const float target = std::min(std::fabs(t), 1.f) * total_;
    int k = int(std::upper_bound(cdf_.begin(), cdf_.end(), target) - cdf_.begin()) - 1;
    k = std::clamp(k, 0, kSegments - 1);
    // |f| is linear within the segment: solve its area for the fraction s.
    const float area = std::max(target - cdf_[size_t(k)], 0.f) / h_;
    const float b = std::fabs(f_[size_t(k)]), d = std::fabs(f_[size_t(k + 1)]) - b;
    const float disc = std::max(b * b + 2.f * d * area, 0.f);
    const float denom = b + std::sqrt(disc);
    const float s = denom > 0.f ? std::clamp(2.f * area / denom, 0.f, 1.f) : 0.f;
    const float x = std::min((float(k) + s) * h_, radius_);
    return {t < 0.f ? -x : x, sign_at(k, s)};
  }

  // g(x): what a splat at offset x weighs (integrates to 1 over the axis).
  float weight(float x) const {
    const float a = std::fabs(x) / h_;
    if (!(a < float(kSegments))) return 0.f;
    const int k = std::min(int(a), kSegments - 1);
    const float s = a - float(k);
    const float b = std::fabs(f_[size_t(k)]), e = std::fabs(f_[size_t(k + 1)]);
    const float q = (b + (e - b) * s) / (2.f * total_);
    return (sign_at(k, s) ? -q : q) * normalisation_;
  }

  // Whether the filter can normalise: its magnitude and its signed
  // integral positive (parameters such as Mitchell's B and C can make
  // either fail).
  bool valid() const { return total_ > 0.f && normalisation_ > 0.f && std::isfinite(normalisation_); }

 private:
  // Whether the interpolated f is negative at fraction s of segment k.
  bool sign_at(int k, float s) const {
    const float a = f_[size_t(k)], b = f_[size_t(k + 1)];
    return a + (b - a) * s < 0.f;
  }

  float radius_ = 1.f, h_ = 1.f / float(kSegments);
  float total_ = 1.f;          // the table's area over [0, radius]
  float normalisation_ = 1.f;  // 1 / Z
  std::array<float, kSegments + 1> f_{}, cdf_{};
};

// Mitchell and Netravali's cubic (1988, eq. 8) with parameters B and C, on
// [0, 2]; pbrt-v4's "mitchell" evaluates it at 2 |x| / radius.
inline double mitchell_1d(double x, double B, double C) {
  x = std::fabs(x);
  if (x < 1.0) return ((12.0 - 9.0 * B - 6.0 * C) * x * x * x + (-18.0 + 12.0 * B + 6.0 * C) * x * x + (6.0 - 2.0 * B)) / 6.0;
  if (x < 2.0)
    return ((-B - 6.0 * C) * x * x * x + (6.0 * B + 30.0 * C) * x * x + (-12.0 * B - 48.0 * C) * x + (8.0 * B + 24.0 * C)) /
           6.0;
  return 0.0;
}

// The Lanczos-windowed sinc, sinc(x) sinc(x / tau) within the radius
// (pbrt-v4's "sinc"), sinc(x) = sin(pi x) / (pi x).
inline double windowed_sinc(double x, double radius, double tau) {
  const auto sinc = [](double v) {
    const double pv = 3.14159265358979323846 * v;
    return std::fabs(v) < 1e-5 ? 1.0 - pv * pv / 6.0 : std::sin(pv) / pv;
  };
  return std::fabs(x) > radius ? 0.0 : sinc(x) * sinc(x / tau);
}

}  // namespace lantern
