#include "geometry/quadric.h"

#include <glm/gtc/matrix_inverse.hpp>

namespace lantern {

namespace {

// Whether an object-space hit point lies within the partial surface's phi
// range; sets *phi.
bool within_phi(const Quadric& q, double x, double y, double* phi) {
  double f = std::atan2(y, x);
  if (f < 0.0) f += 2.0 * 3.14159265358979323846;
  *phi = f;
  return f <= double(q.phi_max);
}

// The two roots of a t^2 + 2 hb t + c = 0 given disc = hb^2 - a c >= 0,
// in ascending order, by the cancellation-free form.
void roots(double a, double hb, double c, double disc, double* t0, double* t1) {
  double s = -(hb + std::copysign(std::sqrt(disc), hb));
  if (s == 0.0) {
    *t0 = *t1 = 0.0;
    return;
  }
  *t0 = s / a;
  *t1 = c / s;
  if (*t0 > *t1) std::swap(*t0, *t1);
}

bool sphere_candidate(const Quadric& q, const glm::dvec3& o, const glm::dvec3& d, double t, QuadricHit* hit) {
  glm::dvec3 p = o + t * d;
  const double r = q.radius;
  double len = glm::length(p);
  if (len > 0.0) p *= r / len;  // back onto the surface
  if ((q.z_min > -q.radius && p.z < q.z_min) || (q.z_max < q.radius && p.z > q.z_max)) return false;
  double phi;
  if (!within_phi(q, p.x, p.y, &phi)) return false;
  double theta = std::acos(glm::clamp(p.z / r, -1.0, 1.0));
  hit->t = t;
  hit->uv = Vec2(float(phi / q.phi_max), float((theta - q.theta_z_min) / (double(q.theta_z_max) - q.theta_z_min)));
  return true;
}

bool cylinder_candidate(const Quadric& q, const glm::dvec3& o, const glm::dvec3& d, double t, QuadricHit* hit) {
  glm::dvec3 p = o + t * d;
  if (p.z < q.z_min || p.z > q.z_max) return false;
  double phi;
  if (!within_phi(q, p.x, p.y, &phi)) return false;
  hit->t = t;
  hit->uv = Vec2(float(phi / q.phi_max), float((p.z - q.z_min) / (double(q.z_max) - q.z_min)));
  return true;
}

}  // namespace

float quadric_object_area(const Quadric& q) {
  switch (q.kind) {
    case QuadricKind::Sphere:
    case QuadricKind::Cylinder: return q.phi_max * q.radius * (q.z_max - q.z_min);
    case QuadricKind::Disk: return 0.5f * q.phi_max * (sqr(q.radius) - sqr(q.inner_radius));
  }
  return 0.f;
}

Vec3 quadric_object_point(const Quadric& q, Vec2 uv) {
  const float phi = uv.x * q.phi_max, c = std::cos(phi), s = std::sin(phi);
  switch (q.kind) {
    case QuadricKind::Sphere: {
      float theta = q.theta_z_min + uv.y * (q.theta_z_max - q.theta_z_min);
      float st = std::sin(theta);
      return q.radius * Vec3(st * c, st * s, std::cos(theta));
    }
    case QuadricKind::Cylinder: return Vec3(q.radius * c, q.radius * s, q.z_min + uv.y * (q.z_max - q.z_min));
    case QuadricKind::Disk: {
      float r = q.radius - uv.y * (q.radius - q.inner_radius);
      return Vec3(r * c, r * s, q.z_min);
    }
  }
  return Vec3(0.f);
}

Vec3 quadric_object_normal(const Quadric& q, const Vec3& p) {
  switch (q.kind) {
    case QuadricKind::Sphere: return p;
    case QuadricKind::Cylinder: return Vec3(p.x, p.y, 0.f);
    case QuadricKind::Disk: return Vec3(0.f, 0.f, 1.f);
  }
  return Vec3(0.f, 0.f, 1.f);
}

Vec2 quadric_sample_uv(const Quadric& q, Vec2 u) {
  switch (q.kind) {
    case QuadricKind::Sphere: {  // uniform in z and phi is uniform in area (Archimedes)
      float z = q.z_min + u.x * (q.z_max - q.z_min);
      float theta = std::acos(glm::clamp(z / q.radius, -1.f, 1.f));
      return Vec2(u.y, glm::clamp((theta - q.theta_z_min) / (q.theta_z_max - q.theta_z_min), 0.f, 1.f));
    }
    case QuadricKind::Cylinder: return Vec2(u.y, u.x);
    case QuadricKind::Disk: {
      float r = std::sqrt(sqr(q.inner_radius) + u.x * (sqr(q.radius) - sqr(q.inner_radius)));
      return Vec2(u.y, glm::clamp((q.radius - r) / (q.radius - q.inner_radius), 0.f, 1.f));
    }
  }
  return u;
}

QuadricCheck finish_quadric(Quadric& q, const glm::dmat4& M) {
  const glm::dmat3 L(M);
  const double det = glm::determinant(L);
  if (!std::isfinite(det) || !is_finite(Vec3(glm::dvec3(M[3])))) return QuadricCheck::OutOfRange;
  if (!(std::fabs(det) > 1e-300)) return QuadricCheck::Singular;
  const float object_area = quadric_object_area(q);
  if (!std::isfinite(object_area)) return QuadricCheck::OutOfRange;
  if (!(object_area > 0.f)) return QuadricCheck::NoArea;
  q.world_from_object = M;
  q.object_from_world = glm::inverse(M);
  q.linear = glm::mat3(L);
  q.normal_to_world = glm::mat3(glm::inverseTranspose(L));
  q.inv_area_scale = float(1.0 / (double(object_area) * std::fabs(det)));
  // The world area is the mean of 1 / density over uniformly placed points:
  // exact under uniform scale, a quadrature under any other.
  constexpr int kGrid = 32;
  double sum = 0.0;
  for (int i = 0; i < kGrid; ++i)
    for (int j = 0; j < kGrid; ++j) {
      Vec2 uv = quadric_sample_uv(q, Vec2((i + 0.5f) / kGrid, (j + 0.5f) / kGrid));
      Vec3 n = glm::normalize(q.normal_to_world * quadric_object_normal(q, quadric_object_point(q, uv)));
      sum += 1.0 / quadric_area_density(q, n);
    }
  q.world_area = float(sum / (kGrid * kGrid));
  const double stretch = std::max({glm::length(L[0]), glm::length(L[1]), glm::length(L[2])});
  const double extent = std::max({double(q.radius), std::fabs(double(q.z_min)), std::fabs(double(q.z_max))});
  const glm::dvec3 t(M[3]);
  q.error_scale = float(std::max({std::fabs(t.x), std::fabs(t.y), std::fabs(t.z)}) + stretch * extent);
  if (!std::isfinite(q.world_area) || !std::isfinite(q.error_scale) || !std::isfinite(q.inv_area_scale))
    return QuadricCheck::OutOfRange;
  return q.world_area > 0.f && q.inv_area_scale > 0.f ? QuadricCheck::Ok : QuadricCheck::NoArea;
}

void quadric_bounds(const Quadric& q, Vec3* lo, Vec3* hi) {
  const double r = q.radius;
  const glm::dvec3 a(-r, -r, q.z_min), b(r, r, q.z_max);
  glm::dvec3 mn(std::numeric_limits<double>::infinity()), mx(-std::numeric_limits<double>::infinity());
  for (int k = 0; k < 8; ++k) {
    glm::dvec3 c((k & 1) ? b.x : a.x, (k & 2) ? b.y : a.y, (k & 4) ? b.z : a.z);
    glm::dvec3 w(q.world_from_object * glm::dvec4(c, 1.0));
    mn = glm::min(mn, w);
    mx = glm::max(mx, w);
  }
  const double pad = 1e-6 * std::max({glm::length(mx - mn), std::fabs(mn.x), std::fabs(mn.y), std::fabs(mn.z),
                                      std::fabs(mx.x), std::fabs(mx.y), std::fabs(mx.z)});
  *lo = Vec3(mn - pad);
  *hi = Vec3(mx + pad);
}

bool intersect_quadric(const Quadric& q, const glm::dvec3& ow, const glm::dvec3& dw, double t_min, double t_max,
                       QuadricHit* hit) {
  // The ray in object space; t is the same parameter in both spaces.
  const glm::dvec3 o(q.object_from_world * glm::dvec4(ow, 1.0));
  const glm::dvec3 d = glm::dmat3(q.object_from_world) * dw;
  const double r = q.radius;
  if (q.kind == QuadricKind::Disk) {
    if (d.z == 0.0) return false;
    double t = (double(q.z_min) - o.z) / d.z;
    if (!(t > t_min && t < t_max)) return false;
    double x = o.x + t * d.x, y = o.y + t * d.y, dist2 = x * x + y * y;
    if (dist2 > r * r || dist2 < double(q.inner_radius) * q.inner_radius) return false;
    double phi;
    if (!within_phi(q, x, y, &phi)) return false;
    hit->t = t;
    hit->uv = Vec2(float(phi / q.phi_max), float((r - std::sqrt(dist2)) / (r - q.inner_radius)));
    return true;
  }
  // a t^2 + 2 hb t + c = 0, with the discriminant hb^2 - a c formed as
  // a (r^2 - |f|^2), f the ray's closest approach to the axis or centre:
  // accurate for a small shape seen from far away.
  double a, hb, c, disc;
  if (q.kind == QuadricKind::Sphere) {
    a = glm::dot(d, d);
    hb = glm::dot(o, d);
    c = glm::dot(o, o) - r * r;
    glm::dvec3 f = o - (hb / a) * d;
    disc = a * (r * r - glm::dot(f, f));
  } else {
    a = d.x * d.x + d.y * d.y;
    if (a == 0.0) return false;  // parallel to the axis
    hb = o.x * d.x + o.y * d.y;
    c = o.x * o.x + o.y * o.y - r * r;
    double fx = o.x - (hb / a) * d.x, fy = o.y - (hb / a) * d.y;
    disc = a * (r * r - (fx * fx + fy * fy));
  }
  if (!(disc >= 0.0) || !(a > 0.0)) return false;
  double t0, t1;
  roots(a, hb, c, disc, &t0, &t1);
  for (double t : {t0, t1}) {
    if (!(t > t_min && t < t_max)) continue;
    bool ok = q.kind == QuadricKind::Sphere ? sphere_candidate(q, o, d, t, hit) : cylinder_candidate(q, o, d, t, hit);
    if (ok) return true;
  }
  return false;
}

}  // namespace lantern
