#include "math/spherical_triangle.h"

#include <algorithm>
#include <cmath>

namespace lantern {

namespace {

constexpr double kPiD = 3.14159265358979323846;

// The angle between unit vectors, accurate near 0 and pi as acos is not.
double angle_between(const glm::dvec3& u, const glm::dvec3& v) {
  if (glm::dot(u, v) < 0.0) return kPiD - 2.0 * std::asin(std::min(glm::length(u + v) / 2.0, 1.0));
  return 2.0 * std::asin(std::min(glm::length(v - u) / 2.0, 1.0));
}

// The part of v orthogonal to unit vector w, normalised; zero if none.
glm::dvec3 orthogonal_unit(const glm::dvec3& v, const glm::dvec3& w) {
  const glm::dvec3 o = v - glm::dot(v, w) * w;
  const double len = glm::length(o);
  return len > 0.0 ? o / len : glm::dvec3(0.0);
}

}  // namespace

SphericalTriangle spherical_triangle(const Vec3& p, const Vec3& v0, const Vec3& v1, const Vec3& v2) {
  SphericalTriangle t;
  const glm::dvec3 o(p);
  const glm::dvec3 d0 = glm::dvec3(v0) - o, d1 = glm::dvec3(v1) - o, d2 = glm::dvec3(v2) - o;
  const double l0 = glm::length(d0), l1 = glm::length(d1), l2 = glm::length(d2);
  if (!(l0 > 0.0 && l1 > 0.0 && l2 > 0.0)) return t;
  t.a = d0 / l0;
  t.b = d1 / l1;
  t.c = d2 / l2;
  // The great circles' normals: arcs AB, BC, CA.
  glm::dvec3 n_ab = glm::cross(t.a, t.b), n_bc = glm::cross(t.b, t.c), n_ca = glm::cross(t.c, t.a);
  const double s_ab = glm::length(n_ab), s_bc = glm::length(n_bc), s_ca = glm::length(n_ca);
  if (!(s_ab > 0.0 && s_bc > 0.0 && s_ca > 0.0)) return t;
  n_ab /= s_ab;
  n_bc /= s_bc;
  n_ca /= s_ca;
  // Each vertex's angle is the one between the planes of its two arcs.
  t.alpha = angle_between(n_ab, -n_ca);
  const double beta = angle_between(n_bc, -n_ab), gamma = angle_between(n_ca, -n_bc);
  const double excess = t.alpha + beta + gamma - kPiD;
  t.solid_angle = std::isfinite(excess) ? std::max(excess, 0.0) : 0.0;
  return t;
}

Vec3 sample_spherical_triangle(const SphericalTriangle& t, Vec2 u) {
  // Arvo's step 1: the sub-triangle A, B, C' of area u.x * solid_angle;
  // C' on the arc from A to C where its angle at B makes that area.
  const double area = double(u.x) * t.solid_angle;
  const double s = std::sin(area - t.alpha), c = std::cos(area - t.alpha);
  const double cos_alpha = std::cos(t.alpha), sin_alpha = std::sin(t.alpha);
  const double cos_arc_ab = glm::dot(t.a, t.b);
  const double uu = c - cos_alpha, vv = s + sin_alpha * cos_arc_ab;
  const double den = (vv * s + uu * c) * sin_alpha;
  double q = den != 0.0 ? ((vv * c - uu * s) * cos_alpha - vv) / den : 1.0;
  q = std::isfinite(q) ? std::clamp(q, -1.0, 1.0) : 1.0;
  const glm::dvec3 c_prime = q * t.a + std::sqrt(std::max(0.0, 1.0 - q * q)) * orthogonal_unit(t.c, t.a);
  // Step 2: the point along the arc from B to C', uniform in the cosine.
  const double z = 1.0 - double(u.y) * (1.0 - glm::dot(c_prime, t.b));
  const glm::dvec3 w = z * t.b + std::sqrt(std::max(0.0, 1.0 - z * z)) * orthogonal_unit(c_prime, t.b);
  return Vec3(glm::normalize(w));
}

Vec2 invert_spherical_triangle(const SphericalTriangle& t, const Vec3& w_in) {
  const glm::dvec3 w = glm::normalize(glm::dvec3(w_in));
  // C' is where the great circle through B and w meets the arc from A to C.
  glm::dvec3 c_prime = glm::cross(glm::cross(t.b, w), glm::cross(t.a, t.c));
  const double len = glm::length(c_prime);
  if (!(len > 0.0)) return Vec2(0.f);
  c_prime /= len;
  if (glm::dot(c_prime, t.a + t.c) < 0.0) c_prime = -c_prime;
  // u.x: the area of A, B, C' over the whole (Van Oosterom and Strackee's
  // formula for the sub-triangle's solid angle); u.y: along the arc from B.
  const double sub = 2.0 * std::atan2(std::fabs(glm::dot(t.a, glm::cross(t.b, c_prime))),
                                      1.0 + glm::dot(t.a, t.b) + glm::dot(t.b, c_prime) + glm::dot(c_prime, t.a));
  const double den = 1.0 - glm::dot(c_prime, t.b);
  const double ux = t.solid_angle > 0.0 ? sub / t.solid_angle : 0.0;
  const double uy = den > 0.0 ? (1.0 - glm::dot(w, t.b)) / den : 0.0;
  return Vec2(float(std::clamp(ux, 0.0, 1.0)), float(std::clamp(uy, 0.0, 1.0)));
}

void cosine_warp_weights(const SphericalTriangle& t, const Vec3& n, float w[4]) {
  const glm::dvec3 nd(n);
  auto weight = [&](const glm::dvec3& d) { return float(std::max(std::fabs(glm::dot(nd, d)), 0.01)); };
  w[0] = w[1] = weight(t.b);
  w[2] = weight(t.a);
  w[3] = weight(t.c);
}

}  // namespace lantern
