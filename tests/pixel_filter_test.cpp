// Pixel filter sampling against its density: the sampled offsets must
// follow pixel_filter_density, since light-tracing splats are weighted by
// it while camera samples are drawn by sample_pixel_filter. And the
// Gaussian must be pbrt-v4's: per axis, the normal density less its value
// at the radius.
#include "film/pixel_filter.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <functional>
#include <vector>

#include "film/film.h"

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

// A filter with negative lobes: the signed weight splats use is the filter
// normalised (Mitchell-Netravali's cubic and the windowed sinc against
// their closed forms over a numerical integral), and the camera samples'
// offsets with their signs follow it: over a fine grid of u, the signed
// fraction of samples below x over the signed fraction of all equals the
// weight's integral up to x.
TEST(PixelFilter, SignedFiltersFollowTheirWeights) {
  struct Case {
    const char* name;
    float radius;
    std::function<double(double)> f;
  };
  const Case cases[] = {
      {"mitchell", 2.f, [](double x) { return mitchell_1d(x, 1.0 / 3.0, 1.0 / 3.0); }},
      {"mitchell B 0.8 C 0.1 r 1.5", 1.5f, [](double x) { return mitchell_1d(2.0 * x / 1.5, 0.8, 0.1); }},
      {"sinc", 4.f, [](double x) { return windowed_sinc(x, 4.0, 3.0); }},
  };
  for (const Case& c : cases) {
    const SignedFilterTable t(c.radius, [&](double x) { return c.f(x); });
    ASSERT_TRUE(t.valid()) << c.name;
    const int n = 40000;
    double integral = 0.0, negative = 0.0;
    for (int i = 0; i < n; ++i) {
      const double x = -c.radius + 2.0 * c.radius * (i + 0.5) / n;
      integral += c.f(x) * 2.0 * c.radius / n;
      negative += std::fmin(c.f(x), 0.0) * 2.0 * c.radius / n;
    }
    EXPECT_LT(negative, 0.0) << c.name << " has negative lobes";
    double worst = 0.0;
    for (int i = 0; i <= 2000; ++i) {
      const double x = -c.radius + 2.0 * c.radius * i / 2000.0;
      worst = std::max(worst, std::fabs(t.weight(float(x)) - c.f(x) / integral));
    }
    EXPECT_LT(worst, 2e-3 * c.f(0.0) / integral) << c.name;
    EXPECT_EQ(t.weight(c.radius + 0.01f), 0.f);
    const int m = 1 << 16;
    std::vector<std::pair<float, int>> xs(m);
    double signed_total = 0.0;
    for (int i = 0; i < m; ++i) {
      const auto sm = t.sample((float(i) + 0.5f) / float(m));
      ASSERT_LE(std::fabs(sm.x), c.radius);
      ASSERT_EQ(sm.negative, c.f(sm.x) < 0.0) << c.name << " at " << sm.x;
      xs[size_t(i)] = {sm.x, sm.negative ? -1 : 1};
      signed_total += sm.negative ? -1.0 : 1.0;
    }
    std::sort(xs.begin(), xs.end());
    double cdf = 0.0, signed_below = 0.0, err = 0.0;
    size_t below = 0;
    const int k = 4000;
    for (int j = 1; j <= k; ++j) {
      const float x0 = -c.radius + 2.f * c.radius * float(j - 1) / float(k), x1 = x0 + 2.f * c.radius / float(k);
      cdf += 0.5 * (double(t.weight(x0)) + t.weight(x1)) * (x1 - x0);
      while (below < xs.size() && xs[below].first < x1) signed_below += xs[below++].second;
      err = std::max(err, std::fabs(signed_below / signed_total - cdf));
    }
    EXPECT_LT(err, 2e-3) << c.name;
  }
}

// A film with a signed filter divides each pixel's signed sum by its
// signed count (pbrt-v4's sum of weights), and keeps the negative counts
// through add and its saved state.
TEST(PixelFilter, FilmKeepsSignedCounts) {
  PixelFilter f;
  f.radius = Vec2(2.f);
  ASSERT_TRUE(make_mitchell_filter(f, 1.0 / 3.0, 1.0 / 3.0));
  Film film(2, 1, f);
  WaveOutput out;
  // Pixel 0: 3 positive samples of 1 and one negative of 2: (3 - 2) / (3 - 1).
  for (int i = 0; i < 3; ++i) out.samples.push_back({0, RGB(1.f), false, false});
  out.samples.push_back({0, RGB(2.f), false, true});
  out.samples.push_back({1, RGB(0.5f), false, false});
  film.prepare(out);
  film.merge(out);
  Image img = film.resolve();
  EXPECT_FLOAT_EQ(img.rgb[0], 0.5f);
  EXPECT_FLOAT_EQ(img.rgb[3], 0.5f);
  struct Bytes : StateWriter, StateReader {
    std::vector<char> b;
    size_t at = 0;
    void write(const void* p, size_t n) override { b.insert(b.end(), (const char*)p, (const char*)p + n); }
    void read(void* p, size_t n) override {
      ASSERT_LE(at + n, b.size());
      std::memcpy(p, b.data() + at, n);
      at += n;
    }
  } bytes;
  film.write_state(bytes);
  Film restored(0, 0, PixelFilter{});
  restored.read_state(bytes);
  EXPECT_EQ(restored.resolve().rgb, img.rgb);
  restored.add(film);  // twice the samples, the same ratio
  EXPECT_FLOAT_EQ(restored.resolve().rgb[0], 0.5f);
}

// The share of a splat's square that stays in the pixels' variances
// (splat_square_share, which bdpt's pilot counts): 1 for a box of one
// pixel (a splat lands whole in one), 4 x (1/4)^2 for a box of radius 1
// (four pixels of a quarter each), and near 1 / (4 pi sigma^2) = 0.32 for
// pbrt-v4's default Gaussian (sigma 0.5, cut at 1.5 and offset to zero
// there). Summing the weights instead of their squares gives 1 for all.
TEST(PixelFilter, SplatSquareShareIsTheSumOfSquaredWeights) {
  PixelFilter box;
  box.type = PixelFilter::Type::Box;
  box.radius = Vec2(0.5f);
  EXPECT_NEAR(splat_square_share(box), 1.0, 1e-6);
  box.radius = Vec2(1.f);
  EXPECT_NEAR(splat_square_share(box), 0.25, 1e-6);
  const PixelFilter gaussian;  // (the default: pbrt-v4's)
  std::printf("  Gaussian's share: %.3f\n", splat_square_share(gaussian));
  EXPECT_GT(splat_square_share(gaussian), 0.25);
  EXPECT_LT(splat_square_share(gaussian), 0.4);
}

}  // namespace
}  // namespace lantern
