// Pixel filter sampling against its density: the sampled offsets must
// follow pixel_filter_density, since light-tracing splats are weighted by
// it while camera samples are drawn by sample_pixel_filter.
#include <gtest/gtest.h>

#include <cmath>

#include "film/pixel_filter.h"

namespace lantern {
namespace {

// The truncated normal's inverse CDF by bisection in double precision.
double gaussian_offset_reference(double u, double radius, double sigma) {
  auto cdf = [&](double x) { return std::erf(x / (sigma * std::sqrt(2.0))); };
  double lo = -radius, hi = radius, target = cdf(-radius) + u * (cdf(radius) - cdf(-radius));
  for (int i = 0; i < 200; ++i) {
    double mid = 0.5 * (lo + hi);
    (cdf(mid) < target ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

TEST(PixelFilter, GaussianOffsetsInvertTheTruncatedCdf) {
  for (auto [radius, sigma] : {std::pair{1.5f, 0.5f}, std::pair{2.f, 2.f}, std::pair{1.5f, 0.1f}, std::pair{0.5f, 3.f}}) {
    double worst = 0.0;
    for (int i = 0; i <= 4096; ++i) {
      float u = std::min(float(i) / 4096.f, 0x1.fffffep-1f);
      float x = sample_gaussian_offset(u, radius, sigma);
      ASSERT_TRUE(std::isfinite(x));
      ASSERT_LE(std::fabs(x), radius);
      double ref = gaussian_offset_reference(u, radius, sigma);
      // Compare where the CDF is steep enough for u to pin x down.
      double density = std::exp(-ref * ref / (2.0 * sigma * sigma));
      if (density > 1e-3) worst = std::max(worst, std::fabs(double(x) - ref) / radius);
    }
    EXPECT_LT(worst, 2e-6) << "radius " << radius << ", sigma " << sigma;
  }
}

}  // namespace
}  // namespace lantern
