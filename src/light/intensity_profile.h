// Point lights whose intensity varies with direction by an image: pbrt-v4's
// "goniometric" light (a grey equal-area map of the sphere of directions,
// measured luminaires) and "projection" light (an image thrown through a
// perspective frustum, a slide projector). Both are point lights with a
// profile: I(w) = I * profile(w). Plain point lights have none and pay
// nothing for it.
#pragma once

#include <glm/mat3x3.hpp>

#include "math/distribution.h"
#include "texture/texture.h"

namespace lantern {

enum class ProfileKind : uint8_t { Goniometric, Projection };

struct IntensityProfile {
  ProfileKind kind = ProfileKind::Goniometric;
  glm::mat3 light_from_world{1.f};  // includes pbrt's axis swap (goniometric) or y flip (projection)
  glm::mat3 world_from_light{1.f};
  int32_t image = -1;  // TexturePools image, read at the nearest texel as pbrt-v4 does
  // Projection: the screen window [lo, hi] on the plane z = 1 / tan_half.
  Vec2 screen_lo{-1.f}, screen_hi{1.f};
  float tan_half = 1.f;
  float hither = 1e-3f;         // directions with z below this (light space) get nothing
  Distribution2D distribution;  // over the image's texels, for light subpaths
  float mean_intensity = 0.f;   // the profile's mean over the sphere: power / (4 pi I)
};

// The profile's factor in world direction w (unit, leaving the light).
RGB profile_value(const IntensityProfile& p, const TexturePools& tex, const Vec3& w);
// Samples a direction leaving the light in proportion to the profile;
// pdf: solid-angle density. Returns false where the profile is zero.
bool sample_profile(const IntensityProfile& p, Vec2 u, Vec3* w, float* pdf);
float profile_pdf(const IntensityProfile& p, const Vec3& w);
// Builds the sampling distribution (each texel's mean channel times the
// solid angle it covers) and the mean over the sphere.
void finalize_profile(IntensityProfile& p, const TexturePools& tex);
// What pbrt-v4's "power" sets: the integral over the sphere of the
// profile's grey value (goniometric) or luminance (projection).
float profile_power(const IntensityProfile& p, const TexturePools& tex);

}  // namespace lantern
