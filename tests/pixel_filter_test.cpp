// Pixel filter sampling against its density: the sampled offsets must
// follow pixel_filter_density, since light-tracing splats are weighted by
// it while camera samples are drawn by sample_pixel_filter. And the
// Gaussian must be pbrt-v4's: per axis, the normal density less its value
// at the radius.
#include <gtest/gtest.h>

#include <cmath>

#include "film/pixel_filter.h"

namespace lantern {
namespace {

const std::pair<float, float> kRadiusSigma[] = {{1.5f, 0.5f}, {2.f, 2.f}, {1.5f, 0.1f}, {0.5f, 3.f}};

// The table's density is pbrt-v4's filter, normalised: g(x) - g(r) with
// g(x) = exp(-x^2 / 2 sigma^2), over its integral (by Simpson's rule).
TEST(PixelFilter, GaussianIsPbrtV4sFilter) {
  for (auto rs : kRadiusSigma) {
    const float radius = rs.first, sigma = rs.second;  // (lambdas cannot capture structured bindings in C++17)
    GaussianFilterTable t(radius, sigma);
    auto f = [&](double x) {
      return std::max(0.0, std::exp(-x * x / (2.0 * sigma * sigma)) - std::exp(-double(radius) * radius / (2.0 * sigma * sigma)));
    };
    const int n = 20000;
    double integral = 0.0;
    for (int i = 0; i <= n; ++i) {
      const double x = -radius + 2.0 * radius * i / n;
      integral += f(x) * (i == 0 || i == n ? 1.0 : i % 2 ? 4.0 : 2.0);
    }
    integral *= 2.0 * radius / n / 3.0;
    double worst = 0.0, peak = f(0.0) / integral;
    for (int i = 0; i <= 3000; ++i) {
      const double x = -radius + 2.0 * radius * i / 3000.0;
      worst = std::max(worst, std::fabs(t.density(float(x)) - f(x) / integral));
    }
    EXPECT_LT(worst, 3e-4 * peak) << "radius " << radius << ", sigma " << sigma;
    EXPECT_EQ(t.density(radius), 0.f);
    EXPECT_EQ(t.density(-radius - 0.1f), 0.f);
  }
}

// sample() inverts the table's CDF: the fraction of a fine grid of u below
// a point x equals the density's integral up to x (trapezoids on a fine
// grid), offsets stay within the radius, and they increase with u.
TEST(PixelFilter, GaussianOffsetsFollowTheDensity) {
  for (auto [radius, sigma] : kRadiusSigma) {
    GaussianFilterTable t(radius, sigma);
    const int n = 1 << 16;
    std::vector<float> xs(n);
    for (int i = 0; i < n; ++i) {
      xs[size_t(i)] = t.sample((float(i) + 0.5f) / float(n));
      ASSERT_TRUE(std::isfinite(xs[size_t(i)]));
      ASSERT_LE(std::fabs(xs[size_t(i)]), radius);
      if (i > 0) ASSERT_GE(xs[size_t(i)], xs[size_t(i - 1)]) << "not monotone at u = " << i;
    }
    double worst = 0.0, cdf = 0.0;
    const int m = 4000;
    double prev = t.density(-radius);
    size_t below = 0;
    for (int j = 1; j <= m; ++j) {
      const float x = -radius + 2.f * radius * float(j) / float(m);
      const double d = t.density(x);
      cdf += 0.5 * (prev + d) * (2.0 * radius / m);
      prev = d;
      while (below < xs.size() && xs[below] < x) ++below;
      worst = std::max(worst, std::fabs(double(below) / n - cdf));
    }
    EXPECT_LT(worst, 2e-4) << "radius " << radius << ", sigma " << sigma;
  }
}

}  // namespace
}  // namespace lantern
