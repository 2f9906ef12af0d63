// Orthonormal frames: shading happens in a local frame whose z axis is the
// shading normal.
#pragma once

#include "math/common.h"

namespace lantern {

// Branchless basis from a unit vector (Duff et al. 2017, "Building an
// Orthonormal Basis, Revisited").
inline void coordinate_system(const Vec3& n, Vec3& s, Vec3& t) {
  float sign = std::copysign(1.f, n.z);
  float a = -1.f / (sign + n.z);
  float b = n.x * n.y * a;
  s = Vec3(1.f + sign * n.x * n.x * a, sign * b, -sign * n.x);
  t = Vec3(b, sign + n.y * n.y * a, -n.y);
}

struct Frame {
  Vec3 s, t, n;

  static Frame from_z(const Vec3& n) {
    Frame f;
    f.n = n;
    coordinate_system(n, f.s, f.t);
    return f;
  }
  Vec3 to_local(const Vec3& v) const { return Vec3(glm::dot(v, s), glm::dot(v, t), glm::dot(v, n)); }
  Vec3 from_local(const Vec3& v) const { return s * v.x + t * v.y + n * v.z; }
};

// Local shading-space trigonometry (z is the normal).
inline float cos_theta(const Vec3& w) { return w.z; }
inline float abs_cos_theta(const Vec3& w) { return std::fabs(w.z); }
inline float cos2_theta(const Vec3& w) { return w.z * w.z; }
inline float sin2_theta(const Vec3& w) { return max_num(0.f, 1.f - cos2_theta(w)); }
inline float tan2_theta(const Vec3& w) { return sin2_theta(w) / cos2_theta(w); }
inline float cos_phi(const Vec3& w) {
  float s = std::sqrt(sin2_theta(w));
  return s == 0.f ? 1.f : glm::clamp(w.x / s, -1.f, 1.f);
}
inline float sin_phi(const Vec3& w) {
  float s = std::sqrt(sin2_theta(w));
  return s == 0.f ? 0.f : glm::clamp(w.y / s, -1.f, 1.f);
}
inline bool same_hemisphere(const Vec3& a, const Vec3& b) { return a.z * b.z > 0.f; }

inline Vec3 reflect(const Vec3& wo, const Vec3& n) { return -wo + 2.f * glm::dot(wo, n) * n; }

// Refracts wi about n (both on the same side); eta is the relative index of
// refraction eta_t / eta_i. Returns false on total internal reflection.
inline bool refract(const Vec3& wi, Vec3 n, float eta, float* etap, Vec3* wt) {
  float cos_i = glm::dot(n, wi);
  if (cos_i < 0.f) {
    eta = 1.f / eta;
    cos_i = -cos_i;
    n = -n;
  }
  float sin2_i = max_num(0.f, 1.f - cos_i * cos_i);
  float sin2_t = sin2_i / (eta * eta);
  if (sin2_t >= 1.f) return false;
  float cos_t = safe_sqrt(1.f - sin2_t);
  *wt = -wi / eta + (cos_i / eta - cos_t) * n;
  if (etap) *etap = eta;
  return true;
}

}  // namespace lantern
