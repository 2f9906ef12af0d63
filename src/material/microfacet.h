// The Trowbridge-Reitz (GGX) microfacet distribution with Smith masking and
// sampling of visible normals (Heitz 2018, "Sampling the GGX Distribution of
// Visible Normals").
#pragma once

#include "math/frame.h"
#include "math/sampling.h"

namespace lantern {

struct TrowbridgeReitz {
  float alpha_x, alpha_y;

  // Below this the surface is treated as perfectly smooth (a delta lobe):
  // the density would exceed what float sampling can represent.
  bool effectively_smooth() const { return max_num(alpha_x, alpha_y) < 1e-3f; }

  float D(const Vec3& wm) const {
    float t2 = tan2_theta(wm);
    if (std::isinf(t2)) return 0.f;
    float c4 = sqr(cos2_theta(wm));
    if (c4 < 1e-16f) return 0.f;
    float e = t2 * (sqr(cos_phi(wm) / alpha_x) + sqr(sin_phi(wm) / alpha_y));
    return 1.f / (kPi * alpha_x * alpha_y * c4 * sqr(1.f + e));
  }
  float lambda(const Vec3& w) const {
    float t2 = tan2_theta(w);
    if (std::isinf(t2)) return 0.f;
    float a2 = sqr(cos_phi(w) * alpha_x) + sqr(sin_phi(w) * alpha_y);
    return (std::sqrt(1.f + a2 * t2) - 1.f) / 2.f;
  }
  float G1(const Vec3& w) const { return 1.f / (1.f + lambda(w)); }
  float G(const Vec3& wo, const Vec3& wi) const { return 1.f / (1.f + lambda(wo) + lambda(wi)); }
  // Density of visible normals seen from w.
  float D(const Vec3& w, const Vec3& wm) const {
    float c = abs_cos_theta(w);
    if (c == 0.f) return 0.f;
    return G1(w) / c * D(wm) * std::fabs(glm::dot(w, wm));
  }
  float pdf(const Vec3& w, const Vec3& wm) const { return D(w, wm); }

  Vec3 sample_wm(const Vec3& w, Vec2 u) const {
    // Stretch to the hemisphere configuration, sample a projected disk.
    Vec3 wh = glm::normalize(Vec3(alpha_x * w.x, alpha_y * w.y, w.z));
    if (wh.z < 0.f) wh = -wh;
    Vec3 t1 = wh.z < 0.99999f ? glm::normalize(glm::cross(Vec3(0, 0, 1), wh)) : Vec3(1, 0, 0);
    Vec3 t2 = glm::cross(wh, t1);
    Vec2 p = sample_uniform_disk_concentric(u);
    float h = std::sqrt(1.f - p.x * p.x);
    float s = (1.f + wh.z) / 2.f;
    p.y = (1.f - s) * h + s * p.y;
    float pz = safe_sqrt(1.f - p.x * p.x - p.y * p.y);
    Vec3 nh = p.x * t1 + p.y * t2 + pz * wh;
    return glm::normalize(Vec3(alpha_x * nh.x, alpha_y * nh.y, max_num(1e-6f, nh.z)));
  }
};

inline Vec3 face_forward_z(const Vec3& v) { return v.z < 0.f ? -v : v; }

}  // namespace lantern
