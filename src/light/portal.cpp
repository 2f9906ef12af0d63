#include "light/portal.h"

#include <stdexcept>

#include "math/equal_area.h"

namespace lantern {

namespace {

// (u, v) of direction w (render space), and the solid angle per unit
// (u, v) there; false for directions behind the window's plane.
bool uv_of(const PortalMap& m, const Vec3& w, Vec2* uv, float* dw_duv) {
  const Vec3 l = m.frame.to_local(w);
  if (!(l.z > 0.f)) return false;
  const float alpha = std::atan2(l.x, l.z), beta = std::atan2(l.y, l.z);
  *uv = glm::clamp(Vec2((alpha + 0.5f * kPi) / kPi, (beta + 0.5f * kPi) / kPi), Vec2(0.f), Vec2(1.f));
  if (dw_duv) *dw_duv = kPi * kPi * (1.f - l.x * l.x) * (1.f - l.y * l.y) / l.z;
  return true;
}

Vec3 dir_of(const PortalMap& m, Vec2 uv, float* dw_duv) {
  const float x = std::tan((uv.x - 0.5f) * kPi), y = std::tan((uv.y - 0.5f) * kPi);
  const Vec3 l = glm::normalize(Vec3(x, y, 1.f));
  if (dw_duv) *dw_duv = kPi * kPi * (1.f - l.x * l.x) * (1.f - l.y * l.y) / l.z;
  return m.frame.from_local(l);
}

// The rectangle of (u, v) that the window covers seen from p.
bool window(const PortalMap& m, const Vec3& p, Vec2* lo, Vec2* hi) {
  Vec2 a, b;
  if (!uv_of(m, glm::normalize(m.corner[0] - p), &a, nullptr) ||
      !uv_of(m, glm::normalize(m.corner[2] - p), &b, nullptr))
    return false;
  *lo = glm::min(a, b);
  *hi = glm::max(a, b);
  return true;
}

// pbrt-v4 reads the map at the nearest texel.
RGB texel(const PortalMap& m, Vec2 uv) { return m.map.lookup_rgb(uv, ImageFilter::Point, WrapMode::Clamp); }

}  // namespace

PortalMap make_portal(const Vec3 corners[4], const TextureImage& map, const glm::mat3& light_from_world,
                      const RGB& scale) {
  PortalMap m;
  for (int i = 0; i < 4; ++i) m.corner[i] = corners[i];
  const Vec3 e01 = corners[1] - corners[0], e03 = corners[3] - corners[0];
  const Vec3 e12 = corners[2] - corners[1], e32 = corners[2] - corners[3];
  const float l01 = glm::length(e01), l03 = glm::length(e03);
  if (!(l01 > 0.f) || !(l03 > 0.f) || !(glm::length(e12) > 0.f) || !(glm::length(e32) > 0.f))
    throw std::invalid_argument("the portal has coincident corners");
  // Opposite sides parallel and equal, adjacent sides perpendicular (to 1e-3, as pbrt-v4 checks).
  const bool parallel =
      glm::dot(e01, e32) / (l01 * glm::length(e32)) > 0.999f && glm::dot(e12, e03) / (glm::length(e12) * l03) > 0.999f;
  const bool square = std::fabs(glm::dot(e01, e03)) / (l01 * l03) < 1e-3f;
  if (!parallel || !square)
    throw std::invalid_argument("the portal's four points are not the corners of a rectangle, in order");
  m.frame.s = e03 / l03;
  m.frame.t = e01 / l01;
  m.frame.n = glm::cross(m.frame.s, m.frame.t);
  m.area = l01 * l03;
  // Resampled at the map's resolution, bilinearly, across the equal-area
  // square's folded edges.
  TextureImage& r = m.map;
  r.width = map.width;
  r.height = map.height;
  r.texels.resize(size_t(r.width) * size_t(r.height));
  std::vector<float> weights(r.texels.size());
  for (int y = 0; y < r.height; ++y)
    for (int x = 0; x < r.width; ++x) {
      const Vec2 uv((float(x) + 0.5f) / float(r.width), (float(y) + 0.5f) / float(r.height));
      float dw_duv;
      const Vec3 w = dir_of(m, uv, &dw_duv);
      const Vec2 st = equal_area_sphere_to_square(glm::normalize(light_from_world * w));
      const size_t i = size_t(y) * size_t(r.width) + size_t(x);
      r.texels[i] = scale * max(map.lookup_rgb(st, ImageFilter::Bilinear, WrapMode::OctahedralSphere), RGB(0.f));
      weights[i] = (r.texels[i][0] + r.texels[i][1] + r.texels[i][2]) * dw_duv;
    }
  m.distribution = WindowedDistribution2D(weights, r.width, r.height);
  return m;
}

RGB portal_Le(const PortalMap& m, const Vec3& p, const Vec3& w) {
  Vec2 uv, lo, hi;
  if (!uv_of(m, w, &uv, nullptr) || !window(m, p, &lo, &hi)) return RGB(0.f);
  if (uv.x < lo.x || uv.y < lo.y || uv.x > hi.x || uv.y > hi.y) return RGB(0.f);
  return texel(m, uv);
}

bool through_portal(const PortalMap& m, const Vec3& p, const Vec3& w_to_light) {
  Vec2 uv, lo, hi;
  if (!uv_of(m, w_to_light, &uv, nullptr) || !window(m, p, &lo, &hi)) return false;
  return uv.x >= lo.x && uv.y >= lo.y && uv.x <= hi.x && uv.y <= hi.y;
}

bool sample_portal(const PortalMap& m, const Vec3& p, Vec2 u, Vec3* wi, float* pdf, RGB* L) {
  Vec2 lo, hi, uv;
  float pdf_uv, dw_duv;
  if (!window(m, p, &lo, &hi) || !m.distribution.sample(u, lo, hi, &uv, &pdf_uv)) return false;
  *wi = dir_of(m, uv, &dw_duv);
  if (!(dw_duv > 0.f)) return false;
  *pdf = pdf_uv / dw_duv;
  *L = texel(m, uv);
  return std::isfinite(*pdf);
}

float portal_pdf(const PortalMap& m, const Vec3& p, const Vec3& w) {
  Vec2 uv, lo, hi;
  float dw_duv;
  if (!uv_of(m, w, &uv, &dw_duv) || !(dw_duv > 0.f) || !window(m, p, &lo, &hi)) return 0.f;
  return m.distribution.pdf(uv, lo, hi) / dw_duv;
}

bool sample_portal_emission(const PortalMap& m, Vec2 u, Vec3* w_to_light, float* pdf, RGB* L) {
  Vec2 uv;
  float pdf_uv, dw_duv;
  if (!m.distribution.sample(u, Vec2(0.f), Vec2(1.f), &uv, &pdf_uv)) return false;
  *w_to_light = dir_of(m, uv, &dw_duv);
  if (!(dw_duv > 0.f)) return false;
  *pdf = pdf_uv / dw_duv;
  *L = texel(m, uv);
  return std::isfinite(*pdf);
}

float portal_emission_pdf(const PortalMap& m, const Vec3& w_to_light) {
  Vec2 uv;
  float dw_duv;
  if (!uv_of(m, w_to_light, &uv, &dw_duv) || !(dw_duv > 0.f)) return 0.f;
  return m.distribution.pdf(uv, Vec2(0.f), Vec2(1.f)) / dw_duv;
}

float portal_power(const PortalMap& m) {
  // The distribution's integral is that of (r + g + b) dw over the map.
  return m.area * float(m.distribution.integral(Vec2(0.f), Vec2(1.f))) / 3.f;
}

}  // namespace lantern
