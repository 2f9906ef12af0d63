// Spatial and directional bounds of emitters, and the importance of a set
// of emitters for a shading point: Conty Estevez & Kulla 2018, "Importance
// Sampling of Many Lights with Adaptive Tree Splitting", in the form of
// pbrt-v4 (Pharr, Jakob & Humphreys, 4th ed., sec. 12.6.3).
#pragma once

#include <algorithm>

#include "math/common.h"

namespace lantern {

struct LightBounds {
  Vec3 lo{kInfinity}, hi{-kInfinity};  // box around every emitting point
  Vec3 w{0.f, 0.f, 1.f};                // axis of the cone of surface normals
  float phi = 0.f;                      // emitted power
  float cos_theta_o = 1.f;              // the normals lie within theta_o of w
  float cos_theta_e = 0.f;              // light leaves within theta_e of a normal
  bool two_sided = false;

  Vec3 centroid() const { return 0.5f * (lo + hi); }
};

// cos(max(0, a - b)) from the sines and cosines of a and b.
inline float cos_sub_clamped(float sin_a, float cos_a, float sin_b, float cos_b) {
  if (cos_a > cos_b) return 1.f;
  return cos_a * cos_b + sin_a * sin_b;
}
// sin(max(0, a - b)).
inline float sin_sub_clamped(float sin_a, float cos_a, float sin_b, float cos_b) {
  if (cos_a > cos_b) return 0.f;
  return sin_a * cos_b - cos_a * sin_b;
}

// LightBounds with what importance queries need precomputed: the bounding
// sphere, the sines, and the plane behind which a one-sided cluster sends
// nothing. A light BVH node holds one of these.
struct PreparedLightBounds {
  Vec3 centroid{0.f};
  float radius = 0.f;   // of the box's bounding sphere
  Vec3 w{0.f, 0.f, 1.f};
  float phi = 0.f;
  float cos_o = 1.f, sin_o = 0.f, cos_e = 0.f;
  float d2_min = 0.f;   // distances are clamped to this, near the box
  float plane = -kInfinity;  // dot(w, p) <= plane: nothing reaches p
  bool two_sided = false;
};

// One-sided emitters whose light stays within 90 degrees of w light nothing
// behind the plane through the box's corner furthest along w. The cone
// test below uses the box's bounding sphere, which for a flat, wide cluster
// of lights (a ceiling of lamps) reaches far behind it; this test is exact
// and keeps descents out of subtrees that cannot light p.
inline PreparedLightBounds prepare(const LightBounds& b) {
  PreparedLightBounds q;
  q.centroid = b.centroid();
  const Vec3 diag = b.hi - b.lo;
  q.radius = 0.5f * glm::length(diag);
  q.d2_min = q.radius;  // pbrt-v4's clamp: half the diagonal's length
  q.w = b.w;
  q.phi = b.phi;
  q.cos_o = b.cos_theta_o;
  q.sin_o = safe_sqrt(1.f - b.cos_theta_o * b.cos_theta_o);
  q.cos_e = b.cos_theta_e;
  q.two_sided = b.two_sided;
  const float sin_e = safe_sqrt(1.f - b.cos_theta_e * b.cos_theta_e);
  if (!b.two_sided && b.cos_theta_o >= 0.f && b.cos_theta_e >= 0.f &&
      b.cos_theta_o * b.cos_theta_e - q.sin_o * sin_e >= 0.f) {  // theta_o + theta_e <= 90 deg
    const Vec3 lo = b.w * b.lo, hi = b.w * b.hi;
    q.plane = std::min(lo.x, hi.x) + std::min(lo.y, hi.y) + std::min(lo.z, hi.z);
  }
  return q;
}

// An upper bound on the light the bounded emitters send to p (normal n, or
// zero for a point in a medium), up to a constant common to all bounds. It
// is zero only where the emitters cannot light p at all: p outside every
// emission cone, or, for a surface point, every emitter exactly in its
// tangent plane (the cosine factor is taken in absolute value, so that
// transmission is not excluded).
inline float light_importance(const PreparedLightBounds& b, const Vec3& p, const Vec3& n) {
  if (glm::dot(b.w, p) <= b.plane) return 0.f;
  const Vec3 d = p - b.centroid;
  const float dist2 = glm::dot(d, d);
  const float inv_dist = dist2 > 0.f ? 1.f / std::sqrt(dist2) : 0.f;
  const Vec3 wi = dist2 > 0.f ? d * inv_dist : Vec3(0.f, 0.f, 1.f);
  float cos_w = glm::dot(b.w, wi);
  if (b.two_sided) cos_w = std::fabs(cos_w);
  const float sin_w = safe_sqrt(1.f - cos_w * cos_w);
  // The directions from p to the bounds lie within theta_b of -wi.
  float cos_b = -1.f, sin_b = 0.f;
  if (dist2 > b.radius * b.radius) {
    sin_b = b.radius * inv_dist;
    cos_b = safe_sqrt(1.f - sin_b * sin_b);
  }
  // theta' = max(0, theta_w - theta_o - theta_b): the smallest angle
  // between the direction to p and any normal of any emitter.
  const float cos_x = cos_sub_clamped(sin_w, cos_w, b.sin_o, b.cos_o);
  const float sin_x = sin_sub_clamped(sin_w, cos_w, b.sin_o, b.cos_o);
  const float cos_p = cos_sub_clamped(sin_x, cos_x, sin_b, cos_b);
  if (cos_p <= b.cos_e) return 0.f;
  float importance = b.phi * cos_p / std::max(dist2, b.d2_min);
  if (n != Vec3(0.f)) {  // the receiving surface's cosine, bounded the same way
    const float cos_i = std::fabs(glm::dot(wi, n));
    const float sin_i = safe_sqrt(1.f - cos_i * cos_i);
    importance *= cos_sub_clamped(sin_i, cos_i, sin_b, cos_b);
  }
  return std::max(importance, 0.f);
}

}  // namespace lantern
