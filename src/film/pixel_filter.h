// Pixel filters by importance sampling (as pbrt-v4 does): a sample's offset
// from the pixel centre is drawn from the filter, so each sample lands in one
// pixel with weight 1 and no splatting between neighbours is needed.
#pragma once

#include <algorithm>
#include <cmath>

#include "math/sampling.h"
#include "scene/scene.h"

namespace lantern {

// Inverse CDF of the normal truncated to [-radius, radius]. The CDF is
// (erf(x / (sigma sqrt 2)) + m) / 2m with m = erf(radius / (sigma sqrt 2)),
// so x = sigma sqrt(2) erfinv((2u - 1) m). Winitzki's closed-form erfinv
// (relative error ~2e-3) is polished by two Newton steps on erf: offsets
// then follow pixel_filter_density to float precision, which light-tracing
// splats rely on, for 3 erf calls instead of a bisection's 26.
inline float sample_gaussian_offset(float u, float radius, float sigma) {
  const float s2 = sigma * std::sqrt(2.f);
  const float y = (2.f * u - 1.f) * std::erf(radius / s2);
  constexpr float a = 0.147f;
  const float ln = std::log(std::max(1.f - y * y, 1e-30f));
  const float t = 2.f / (kPi * a) + 0.5f * ln;
  float z = std::copysign(std::sqrt(std::max(0.f, std::sqrt(t * t - ln / a) - t)), y);
  for (int i = 0; i < 2; ++i) z -= (std::erf(z) - y) / (1.1283791671f * std::exp(-z * z));  // 2/sqrt(pi) e^(-z^2)
  return std::clamp(z * s2, -radius, radius);
}

inline Vec2 sample_pixel_filter(const PixelFilter& f, Vec2 u) {
  switch (f.type) {
    case PixelFilter::Type::Box: return Vec2((2.f * u.x - 1.f) * f.radius.x, (2.f * u.y - 1.f) * f.radius.y);
    case PixelFilter::Type::Triangle: return Vec2(sample_tent(u.x, f.radius.x), sample_tent(u.y, f.radius.y));
    case PixelFilter::Type::Gaussian:
      return Vec2(sample_gaussian_offset(u.x, f.radius.x, f.sigma), sample_gaussian_offset(u.y, f.radius.y, f.sigma));
  }
  return Vec2(0.f);
}

// A raster position for one camera sample of `pixel` (y * width + x): the
// pixel centre plus an offset drawn from the filter.
inline Vec2 sample_raster_position(const PixelFilter& f, uint32_t pixel, uint32_t width, Vec2 u) {
  Vec2 offset = sample_pixel_filter(f, u);
  return Vec2(float(pixel % width) + 0.5f + offset.x, float(pixel / width) + 0.5f + offset.y);
}

// The density sample_pixel_filter draws offsets from, per axis: what a
// light-tracing splat must weight each pixel with to estimate the same
// pixel integral as the camera samples.
inline float pixel_filter_density_1d(const PixelFilter& f, float x, float r) {
  if (std::fabs(x) >= r) return 0.f;
  switch (f.type) {
    case PixelFilter::Type::Box: return 0.5f / r;
    case PixelFilter::Type::Triangle: return (r - std::fabs(x)) / (r * r);
    case PixelFilter::Type::Gaussian: {
      float norm = std::erf(r / (f.sigma * std::sqrt(2.f)));  // mass of the normal inside [-r, r]
      return std::exp(-x * x / (2.f * f.sigma * f.sigma)) / (f.sigma * std::sqrt(2.f * kPi) * norm);
    }
  }
  return 0.f;
}
inline float pixel_filter_density(const PixelFilter& f, Vec2 offset) {
  return pixel_filter_density_1d(f, offset.x, f.radius.x) * pixel_filter_density_1d(f, offset.y, f.radius.y);
}

}  // namespace lantern
