#include "math/equal_area.h"

namespace lantern {

Vec3 equal_area_square_to_sphere(Vec2 p) {
  float u = 2.f * p.x - 1.f, v = 2.f * p.y - 1.f;
  float up = std::fabs(u), vp = std::fabs(v);
  float signed_distance = 1.f - (up + vp);
  float d = std::fabs(signed_distance);
  float r = 1.f - d;
  float phi = (r == 0.f ? 1.f : (vp - up) / r + 1.f) * kPi / 4.f;
  float z = std::copysign(1.f - r * r, signed_distance);
  float cos_phi = std::copysign(std::cos(phi), u);
  float sin_phi = std::copysign(std::sin(phi), v);
  float s = r * safe_sqrt(2.f - r * r);
  return Vec3(cos_phi * s, sin_phi * s, z);
}

Vec2 equal_area_sphere_to_square(const Vec3& d) {
  float x = std::fabs(d.x), y = std::fabs(d.y), z = std::fabs(d.z);
  float r = safe_sqrt(1.f - z);
  float a = std::fmax(x, y), b = std::fmin(x, y);
  b = a == 0.f ? 0.f : b / a;
  float phi = std::atan(b) * 2.f / kPi;
  if (x < y) phi = 1.f - phi;
  float v = phi * r, u = r - v;
  if (d.z < 0.f) {
    std::swap(u, v);
    u = 1.f - u;
    v = 1.f - v;
  }
  u = std::copysign(u, d.x);
  v = std::copysign(v, d.y);
  return Vec2(glm::clamp((u + 1.f) * 0.5f, 0.f, kOneMinusEpsilon), glm::clamp((v + 1.f) * 0.5f, 0.f, kOneMinusEpsilon));
}

}  // namespace lantern
