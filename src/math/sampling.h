// Warps from the unit square to the domains the renderer samples, each with
// its density.
#pragma once

#include <algorithm>
#include <cmath>

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

// A point t of [0, 1] with density proportional to smoothstep(t) = 3t^2 -
// 2t^3, that is 6t^2 - 4t^3: its cumulative distribution 2t^3 - t^4 is
// inverted by Newton's method, kept inside a bracket that halves when a
// step would leave it (the distribution is increasing on [0, 1]).
inline float sample_smoothstep(float u) {
  // (starting where the distribution's ends are: 2t^3 near 0, 1 - 2(1 - t) near 1)
  float lo = 0.f, hi = 1.f, t = u < 0.5f ? std::cbrt(0.5f * u) : 1.f - 0.5f * (1.f - u);
  for (int i = 0; i < 24; ++i) {
    const float f = t * t * t * (2.f - t) - u, slope = 2.f * t * t * (3.f - 2.f * t);
    if (f == 0.f) break;
    (f < 0.f ? lo : hi) = t;
    float next = slope > 0.f ? t - f / slope : 0.5f * (lo + hi);
    if (!(next > lo && next < hi)) next = 0.5f * (lo + hi);
    if (std::fabs(next - t) < 1e-7f) {
      t = next;
      break;
    }
    t = next;
  }
  return t;
}

// Directions in a cone around +z with density proportional to a spot
// light's falloff: 1 where cos theta >= cos_inner, smoothstep from
// cos_outer (0) to cos_inner (1) between, 0 beyond. Uniform in cos theta
// and phi times that weight, so the mass is 2 pi ((1 - cos_inner) +
// (cos_inner - cos_outer) / 2): the inner cone or the edge is chosen by
// its share, then cos theta within it. A spot light's emission weighed so
// has a constant intensity over density (pbrt-v4 samples its spot lights
// this way too).
// An inner cone no narrower than the outer one (a "conedeltaangle" of 0,
// or more than the cone) leaves a hard edge at cos_outer.
inline float smooth_cone_mass(float cos_inner, float cos_outer) {
  const float inner = std::max(cos_inner, cos_outer);
  return 2.f * kPi * ((1.f - inner) + 0.5f * (inner - cos_outer));
}
inline float smooth_cone_weight(float cos_t, float cos_inner, float cos_outer) {
  if (cos_t >= cos_inner && cos_t >= cos_outer) return 1.f;
  if (cos_t <= cos_outer) return 0.f;
  const float t = (cos_t - cos_outer) / (cos_inner - cos_outer);
  return t * t * (3.f - 2.f * t);
}
inline float smooth_cone_pdf(float cos_t, float cos_inner, float cos_outer) {
  return smooth_cone_weight(cos_t, cos_inner, cos_outer) / smooth_cone_mass(cos_inner, cos_outer);
}
inline Vec3 sample_smooth_cone(Vec2 u, float cos_inner, float cos_outer) {
  cos_inner = std::max(cos_inner, cos_outer);
  const float inner = 1.f - cos_inner, edge = 0.5f * (cos_inner - cos_outer);
  const float p_inner = inner / (inner + edge);
  float cos_t;
  if (u.x < p_inner) {
    cos_t = 1.f - (u.x / p_inner) * inner;
  } else {
    const float v = std::min((u.x - p_inner) / (1.f - p_inner), 0x1.fffffep-1f);
    cos_t = cos_outer + sample_smoothstep(v) * (cos_inner - cos_outer);
  }
  const float sin_t = safe_sqrt(1.f - cos_t * cos_t), phi = u.y * 2.f * kPi;
  return Vec3(std::cos(phi) * sin_t, std::sin(phi) * sin_t, cos_t);
}

// A point of [0, 1] with density proportional to (1 - x) a + x b (a, b >= 0,
// not both 0): the inverse of its cumulative distribution, written so that
// a = b loses no digits.
inline float sample_linear(float u, float a, float b) {
  const float s = std::sqrt((1.f - u) * a * a + u * b * b);
  return a + s > 0.f ? std::min(u * (a + b) / (a + s), 0x1.fffffep-1f) : u;
}

// A point of the unit square with density proportional to the bilinear
// interpolation of w at its corners (w[0] at (0, 0), w[1] at (1, 0), w[2]
// at (0, 1), w[3] at (1, 1); not negative, not all 0): y from its marginal,
// then x given y.
inline Vec2 sample_bilinear(Vec2 u, const float w[4]) {
  const float y = sample_linear(u.y, w[0] + w[1], w[2] + w[3]);
  return Vec2(sample_linear(u.x, (1.f - y) * w[0] + y * w[2], (1.f - y) * w[1] + y * w[3]), y);
}
inline float bilinear_pdf(Vec2 p, const float w[4]) {
  const float sum = w[0] + w[1] + w[2] + w[3];
  if (!(sum > 0.f)) return 1.f;
  return 4.f * ((1.f - p.x) * (1.f - p.y) * w[0] + p.x * (1.f - p.y) * w[1] + (1.f - p.x) * p.y * w[2] +
                p.x * p.y * w[3]) / sum;
}

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
