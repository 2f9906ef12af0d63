// Pixel filters by importance sampling (as pbrt-v4 does): a sample's offset
// from the pixel centre is drawn from the filter, so each sample lands in one
// pixel with weight 1 and no splatting between neighbours is needed.
#pragma once

#include <algorithm>
#include <cmath>

#include "math/sampling.h"
#include "film/gaussian_filter.h"

namespace lantern {

// The scene's pixel filter (pbrt-v4's Filter directive).
struct PixelFilter {
  enum class Type { Box, Triangle, Gaussian } type = Type::Gaussian;
  Vec2 radius{1.5f};
  float sigma = 0.5f;
  GaussianFilterTable gaussian[2];  // per axis, for radius and sigma (pbrt-v4's defaults here)
};

inline Vec2 sample_pixel_filter(const PixelFilter& f, Vec2 u) {
  switch (f.type) {
    case PixelFilter::Type::Box: return Vec2((2.f * u.x - 1.f) * f.radius.x, (2.f * u.y - 1.f) * f.radius.y);
    case PixelFilter::Type::Triangle: return Vec2(sample_tent(u.x, f.radius.x), sample_tent(u.y, f.radius.y));
    case PixelFilter::Type::Gaussian:
      return Vec2(f.gaussian[0].sample(u.x), f.gaussian[1].sample(u.y));
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
inline float pixel_filter_density_1d(const PixelFilter& f, float x, int axis) {
  const float r = f.radius[axis];
  if (std::fabs(x) >= r) return 0.f;
  switch (f.type) {
    case PixelFilter::Type::Box: return 0.5f / r;
    case PixelFilter::Type::Triangle: return (r - std::fabs(x)) / (r * r);
    case PixelFilter::Type::Gaussian: return f.gaussian[axis].density(x);
  }
  return 0.f;
}
inline float pixel_filter_density(const PixelFilter& f, Vec2 offset) {
  return pixel_filter_density_1d(f, offset.x, 0) * pixel_filter_density_1d(f, offset.y, 1);
}

}  // namespace lantern
