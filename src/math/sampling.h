// Warps from the unit square to the domains the renderer samples, each with
// its density.
#pragma once

#include "math/common.h"

namespace lantern {

// Shirley-Chiu concentric mapping, square -> unit disk.
inline Vec2 sample_uniform_disk_concentric(Vec2 u) {
  Vec2 o = 2.f * u - Vec2(1.f);
  if (o.x == 0.f && o.y == 0.f) return Vec2(0.f);
  float r, theta;
  if (std::fabs(o.x) > std::fabs(o.y)) {
    r = o.x;
    theta = (kPi / 4.f) * (o.y / o.x);
  } else {
    r = o.y;
    theta = kPi / 2.f - (kPi / 4.f) * (o.x / o.y);
  }
  return r * Vec2(std::cos(theta), std::sin(theta));
}

inline Vec3 sample_cosine_hemisphere(Vec2 u) {
  Vec2 d = sample_uniform_disk_concentric(u);
  float z = safe_sqrt(1.f - d.x * d.x - d.y * d.y);
  return Vec3(d.x, d.y, z);
}
inline float cosine_hemisphere_pdf(float cos_theta) { return cos_theta * kInvPi; }

// Uniform over the hemisphere around +z: z = u.x, as pbrt-v4 maps it.
inline Vec3 sample_uniform_hemisphere(Vec2 u) {
  float z = u.x;
  float r = safe_sqrt(1.f - z * z);
  float phi = 2.f * kPi * u.y;
  return Vec3(r * std::cos(phi), r * std::sin(phi), z);
}
inline constexpr float uniform_hemisphere_pdf() { return kInv2Pi; }

inline Vec3 sample_uniform_sphere(Vec2 u) {
  float z = 1.f - 2.f * u.x;
  float r = safe_sqrt(1.f - z * z);
  float phi = 2.f * kPi * u.y;
  return Vec3(r * std::cos(phi), r * std::sin(phi), z);
}
inline constexpr float uniform_sphere_pdf() { return kInv4Pi; }

// Uniform direction inside a cone around +z with cos of its half angle.
inline Vec3 sample_uniform_cone(Vec2 u, float cos_max) {
  float cos_t = (1.f - u.x) + u.x * cos_max;
  float sin_t = safe_sqrt(1.f - cos_t * cos_t);
  float phi = u.y * 2.f * kPi;
  return Vec3(std::cos(phi) * sin_t, std::sin(phi) * sin_t, cos_t);
}
inline float uniform_cone_pdf(float cos_max) { return 1.f / (2.f * kPi * (1.f - cos_max)); }

// Uniform barycentrics on a triangle (returns b0, b1; b2 = 1 - b0 - b1),
// using the low-distortion square-to-triangle map of Heitz 2019.
inline Vec2 sample_uniform_triangle(Vec2 u) {
  float b0, b1;
  if (u.x < u.y) {
    b0 = u.x / 2.f;
    b1 = u.y - b0;
  } else {
    b1 = u.y / 2.f;
    b0 = u.x - b1;
  }
  return Vec2(b0, b1);
}

// Sampling a tent of radius r: used for the triangle pixel filter.
inline float sample_tent(float u, float r) {
  if (u < 0.5f) {
    float v = u * 2.f;
    return -r + r * std::sqrt(v);
  }
  float v = (u - 0.5f) * 2.f;
  return r - r * std::sqrt(1.f - v);
}

}  // namespace lantern
