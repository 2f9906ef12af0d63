#include "geometry/bilinear_patch.h"

#include <cmath>

#include "geometry/surface.h"

namespace lantern {

namespace {

glm::dvec3 dv(const Vec3& v) { return glm::dvec3(v); }

double det3(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c) { return glm::dot(a, glm::cross(b, c)); }

// Real roots of c2 x^2 + c1 x + c0 = 0, in the form that loses no digits to
// cancellation; returns how many.
int solve_quadratic(double c2, double c1, double c0, double* r0, double* r1) {
  const double scale = max_num(std::fabs(c2), max_num(std::fabs(c1), std::fabs(c0)));
  if (scale == 0.0) return 0;
  if (std::fabs(c2) <= 1e-12 * scale) {  // linear
    if (c1 == 0.0) return 0;
    *r0 = -c0 / c1;
    return 1;
  }
  const double disc = c1 * c1 - 4.0 * c2 * c0;
  if (disc < 0.0) return 0;
  const double q = -0.5 * (c1 + std::copysign(std::sqrt(disc), c1));
  *r0 = q / c2;
  if (q == 0.0) return 1;
  *r1 = c0 / q;
  return 2;
}

// A per-vertex attribute at (u, v) of patch v.
template <class T>
T bilerp(const std::vector<T>& a, const glm::uvec4& v, Vec2 uv) {
  return glm::mix(glm::mix(a[v.x], a[v.y], uv.x), glm::mix(a[v.z], a[v.w], uv.x), uv.y);
}

constexpr double kEdgeSlack = 1e-9;  // (u, v) this far past an edge still count: no cracks between patches

// A density proportional to (1 - x) a + x b on [0, 1], inverted.
float sample_linear(float u, float a, float b) {
  if (a == b) return u;
  const float x = u * (a + b) / (a + std::sqrt(glm::mix(a * a, b * b, u)));
  return min_num(x, kOneMinusEpsilon);
}

}  // namespace

bool intersect_bilinear_patch(const PatchCorners& c, const glm::dvec3& o, const glm::dvec3& d, double t_min,
                              double t_max, double* t_hit, Vec2* uv) {
  const glm::dvec3 p00 = dv(c.p00), p10 = dv(c.p10), p01 = dv(c.p01), p11 = dv(c.p11);
  // Segment u runs from q(u) = lerp(u, p00, p10) along e(u) = lerp(u, p01, p11) - q(u);
  // the ray meets its line where (q(u) - o) . (d x e(u)) = 0, quadratic in u.
  const glm::dvec3 a0 = p00 - o, a1 = p10 - p00, e0 = p01 - p00, e1 = (p11 - p01) - (p10 - p00);
  const double c0 = glm::dot(a0, glm::cross(d, e0));
  const double c1 = glm::dot(a1, glm::cross(d, e0)) + glm::dot(a0, glm::cross(d, e1));
  const double c2 = glm::dot(a1, glm::cross(d, e1));
  double roots[2];
  const int n = solve_quadratic(c2, c1, c0, &roots[0], &roots[1]);
  bool found = false;
  double best = t_max;
  for (int k = 0; k < n; ++k) {
    const double u = roots[k];
    if (!(u >= -kEdgeSlack && u <= 1.0 + kEdgeSlack)) continue;
    const glm::dvec3 q = p00 + u * a1, e = e0 + u * e1, w = q - o, nrm = glm::cross(d, e);
    const double n2 = glm::dot(nrm, nrm);
    if (!(n2 > 0.0)) continue;
    // o + t d = q + v e: cross with e for t, with d for v.
    const double t = det3(w, e, nrm) / n2, v = det3(w, d, nrm) / n2;
    if (!(v >= -kEdgeSlack && v <= 1.0 + kEdgeSlack) || !(t > t_min && t < best)) continue;
    best = t;
    *t_hit = t;
    *uv = Vec2(float(glm::clamp(u, 0.0, 1.0)), float(glm::clamp(v, 0.0, 1.0)));
    found = true;
  }
  return found;
}

Vec3 patch_cross(const PatchCorners& c, Vec2 uv) {
  const Vec3 dpdu = glm::mix(c.p10 - c.p00, c.p11 - c.p01, uv.y);
  const Vec3 dpdv = glm::mix(c.p01 - c.p00, c.p11 - c.p10, uv.x);
  return glm::cross(dpdu, dpdv);
}

namespace {

// The unit winding normal, oriented towards the interpolated vertex normal
// `ns` when the set has normals, else flipped by flip_normal.
Vec3 oriented_normal(const BilinearPatchSet& s, const PatchCorners& c, Vec2 uv, const Vec3& ns) {
  Vec3 n = patch_cross(c, uv);
  const float len = glm::length(n);
  if (!(len > 0.f) || !std::isfinite(len)) {  // a collapsed corner: the patch's mean normal
    n = patch_cross(c, Vec2(0.5f));
    if (!(glm::length(n) > 0.f)) n = Vec3(0, 0, 1);
  }
  n = glm::normalize(n);
  if (!s.normals.empty()) return glm::dot(n, ns) < 0.f ? -n : n;
  return s.flip_normal ? -n : n;
}

}  // namespace

Vec3 bilinear_normal(const BilinearPatchSet& s, uint32_t i, Vec2 uv) {
  const Vec3 ns = s.normals.empty() ? Vec3(0.f) : bilerp(s.normals, s.patches[i], uv);
  return oriented_normal(s, patch_corners(s, i), uv, ns);
}

// a + t (b - a) from the nearer end: a coordinate a and b share comes out
// exactly (a flat patch in a plane z = c stays on it, as triangle_point's
// points do), and so do the ends themselves.
static Vec3 lerp_from_nearer(const Vec3& a, const Vec3& b, float t) {
  return t <= 0.5f ? a + t * (b - a) : b + (1.f - t) * (a - b);
}

SurfacePoint bilinear_point(const BilinearPatchSet& s, uint32_t i, Vec2 uv) {
  const PatchCorners c = patch_corners(s, i);
  const glm::uvec4 v = s.patches[i];
  SurfacePoint sp;
  sp.p = lerp_from_nearer(lerp_from_nearer(c.p00, c.p10, uv.x), lerp_from_nearer(c.p01, c.p11, uv.x), uv.y);
  const Vec3 ns = s.normals.empty() ? Vec3(0.f) : bilerp(s.normals, v, uv);
  sp.ng = oriented_normal(s, c, uv, ns);
  const float l2 = glm::dot(ns, ns);
  sp.ns = l2 > 0.f ? ns / std::sqrt(l2) : sp.ng;
  Vec2 st[4];
  sp.uv = patch_corner_uvs(s, i, st) ? glm::mix(glm::mix(st[0], st[1], uv.x), glm::mix(st[2], st[3], uv.x), uv.y) : uv;
  sp.error_scale =
      max_num(max_abs_component(sp.p), max_num(max_num(max_abs_component(c.p00), max_abs_component(c.p10)),
                                                   max_num(max_abs_component(c.p01), max_abs_component(c.p11))));
  return sp;
}

float bilinear_area(const PatchCorners& c) {
  // 4-point Gauss-Legendre on [0, 1] in each direction: |dp/du x dp/dv| is
  // the length of an affine function, smooth over the square.
  const double x[4] = {0.0694318442029737, 0.3300094782075719, 0.6699905217924281, 0.9305681557970263};
  const double w[4] = {0.1739274225687269, 0.3260725774312731, 0.3260725774312731, 0.1739274225687269};
  double a = 0.0;
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) a += w[i] * w[j] * double(glm::length(patch_cross(c, Vec2(float(x[i]), float(x[j])))));
  return float(a);
}

namespace {
struct CornerWeights {
  float w00, w10, w01, w11, mean;
};
CornerWeights corner_weights(const PatchCorners& c) {
  CornerWeights w{glm::length(patch_cross(c, Vec2(0, 0))), glm::length(patch_cross(c, Vec2(1, 0))),
                  glm::length(patch_cross(c, Vec2(0, 1))), glm::length(patch_cross(c, Vec2(1, 1))), 0.f};
  w.mean = 0.25f * (w.w00 + w.w10 + w.w01 + w.w11);
  return w;
}
}  // namespace

Vec2 sample_bilinear_patch(const PatchCorners& c, Vec2 u) {
  const CornerWeights w = corner_weights(c);
  if (!(w.mean > 0.f)) return u;
  const float v = sample_linear(u.y, w.w00 + w.w10, w.w01 + w.w11);
  return Vec2(sample_linear(u.x, glm::mix(w.w00, w.w01, v), glm::mix(w.w10, w.w11, v)), v);
}

float bilinear_area_density(const PatchCorners& c, Vec2 uv) {
  const CornerWeights w = corner_weights(c);
  const float jac = glm::length(patch_cross(c, uv));
  if (!(w.mean > 0.f) || !(jac > 0.f)) return 0.f;
  const float pdf_uv = glm::mix(glm::mix(w.w00, w.w10, uv.x), glm::mix(w.w01, w.w11, uv.x), uv.y) / w.mean;
  return pdf_uv / jac;
}

Vec2 bilinear_uv_of(const PatchCorners& c, const Vec3& p) {
  glm::dvec2 uv(0.5);
  for (int k = 0; k < 12; ++k) {
    const Vec2 f(uv);
    const glm::dvec3 q = dv(glm::mix(glm::mix(c.p00, c.p10, f.x), glm::mix(c.p01, c.p11, f.x), f.y));
    const glm::dvec3 du = dv(glm::mix(c.p10 - c.p00, c.p11 - c.p01, f.y)),
                     dvv = dv(glm::mix(c.p01 - c.p00, c.p11 - c.p10, f.x));
    const glm::dvec3 r = dv(p) - q;
    // Least squares: (J^T J) delta = J^T r.
    const double a = glm::dot(du, du), b = glm::dot(du, dvv), d = glm::dot(dvv, dvv);
    const double det = a * d - b * b;
    if (!(std::fabs(det) > 0.0)) break;
    const double ru = glm::dot(du, r), rv = glm::dot(dvv, r);
    uv += glm::dvec2((d * ru - b * rv) / det, (a * rv - b * ru) / det);
    uv = glm::clamp(uv, 0.0, 1.0);
  }
  return Vec2(uv);
}

bool is_parallelogram(const Vec3& v00, const Vec3& v10, const Vec3& v01, const Vec3& v11) {
  const float size =
      max_num(max_num(glm::length(v10 - v00), glm::length(v01 - v00)), max_num(glm::length(v11 - v00), 1e-30f));
  // Corners far from the origin carry the rounding of their coordinates
  // (2^-24 of their size each): a flat panel written at x = 1000 misses
  // its fourth corner by some 1e-5 and is still a parallelogram, two
  // triangles that differ from its patch by less than a float can show.
  const float far = max_num(max_num(max_abs_component(v00), max_abs_component(v10)),
                              max_num(max_abs_component(v01), max_abs_component(v11)));
  return glm::length((v00 + v11) - (v10 + v01)) <= 1e-6f * max_num(size, far);
}

}  // namespace lantern
