// Pixel filters by importance sampling (as pbrt-v4 does): a sample's offset
// from the pixel centre is drawn from the filter, so each sample lands in one
// pixel with weight 1 and no splatting between neighbours is needed. A
// filter with negative lobes (mitchell, sinc) draws from its magnitude and
// gives the sample the filter's sign there (film/signed_filter.h).
#pragma once

#include <algorithm>
#include <cmath>

#include "math/sampling.h"
#include "film/gaussian_filter.h"
#include "film/signed_filter.h"

namespace lantern {

// The scene's pixel filter (pbrt-v4's Filter directive).
struct PixelFilter {
  enum class Type { Box, Triangle, Gaussian, Mitchell, Sinc } type = Type::Gaussian;
  Vec2 radius{1.5f};
  float sigma = 0.5f;
  GaussianFilterTable gaussian[2];  // per axis, for radius and sigma (pbrt-v4's defaults here)
  SignedFilterTable lobed[2];       // per axis: mitchell and sinc
  // Whether samples carry signs: the film then keeps signed counts.
  bool is_signed() const { return type == Type::Mitchell || type == Type::Sinc; }
};

inline Vec2 sample_pixel_filter(const PixelFilter& f, Vec2 u) {
  switch (f.type) {
    case PixelFilter::Type::Box: return Vec2((2.f * u.x - 1.f) * f.radius.x, (2.f * u.y - 1.f) * f.radius.y);
    case PixelFilter::Type::Triangle: return Vec2(sample_tent(u.x, f.radius.x), sample_tent(u.y, f.radius.y));
    case PixelFilter::Type::Gaussian:
      return Vec2(f.gaussian[0].sample(u.x), f.gaussian[1].sample(u.y));
    case PixelFilter::Type::Mitchell:
    case PixelFilter::Type::Sinc: return Vec2(f.lobed[0].sample(u.x).x, f.lobed[1].sample(u.y).x);
  }
  return Vec2(0.f);
}

// A filter of negative lobes, `type`, from its 1D profile filter_1d(x, r)
// for each axis of radius r; false when it cannot normalise
// (SignedFilterTable::valid).
template <class Filter1D>
inline bool make_lobed_filter(PixelFilter& f, PixelFilter::Type type, Filter1D&& filter_1d) {
  f.type = type;
  for (int axis = 0; axis < 2; ++axis) {
    const double r = f.radius[axis];
    f.lobed[axis] = SignedFilterTable(r, [&](double x) { return filter_1d(x, r); });
  }
  return f.lobed[0].valid() && f.lobed[1].valid();
}
// pbrt-v4's "mitchell" (Mitchell-Netravali's B and C) and "sinc" (a
// Lanczos-windowed sinc of tau) filters for f.radius.
inline bool make_mitchell_filter(PixelFilter& f, double B, double C) {
  return make_lobed_filter(f, PixelFilter::Type::Mitchell,
                           [&](double x, double r) { return mitchell_1d(2.0 * x / r, B, C); });
}
inline bool make_sinc_filter(PixelFilter& f, double tau) {
  return make_lobed_filter(f, PixelFilter::Type::Sinc, [&](double x, double r) { return windowed_sinc(x, r, tau); });
}

// The sign of the filter at the offset sample_pixel_filter draws for u:
// whether the camera sample counts negatively (false for filters without
// negative lobes). Integrators ask it when they hand the sample to the
// film, from the same sampler dimensions.
inline bool pixel_filter_negative(const PixelFilter& f, Vec2 u) {
  if (!f.is_signed()) return false;
  return f.lobed[0].sample(u.x).negative != f.lobed[1].sample(u.y).negative;
}

// A raster position for one camera sample of `pixel` (y * width + x): the
// pixel centre plus an offset drawn from the filter.
inline Vec2 sample_raster_position(const PixelFilter& f, uint32_t pixel, uint32_t width, Vec2 u) {
  Vec2 offset = sample_pixel_filter(f, u);
  return Vec2(float(pixel % width) + 0.5f + offset.x, float(pixel / width) + 0.5f + offset.y);
}

// The density sample_pixel_filter draws offsets from, per axis (for a
// signed filter, that density times the sign, normalised: the filter the
// film's signed counts make of the samples): what a light-tracing splat
// must weight each pixel with to estimate the same pixel integral as the
// camera samples.
inline float pixel_filter_density_1d(const PixelFilter& f, float x, int axis) {
  const float r = f.radius[axis];
  if (std::fabs(x) >= r) return 0.f;
  switch (f.type) {
    case PixelFilter::Type::Box: return 0.5f / r;
    case PixelFilter::Type::Triangle: return (r - std::fabs(x)) / (r * r);
    case PixelFilter::Type::Gaussian: return f.gaussian[axis].density(x);
    case PixelFilter::Type::Mitchell:
    case PixelFilter::Type::Sinc: return f.lobed[axis].weight(x);
  }
  return 0.f;
}
inline float pixel_filter_density(const PixelFilter& f, Vec2 offset) {
  return pixel_filter_density_1d(f, offset.x, 0) * pixel_filter_density_1d(f, offset.y, 1);
}

}  // namespace lantern
