#include "geometry/nurbs.h"

#include <algorithm>
#include <cmath>

namespace lantern {

namespace {

// The knot span [k[s], k[s + 1]) holding t, among the valid spans
// order - 1 .. n - 1; the end of the range belongs to the last one.
int find_span(const std::vector<float>& k, int n, int order, double t) {
  int s = order - 1;
  while (s < n - 1 && double(k[size_t(s + 1)]) <= t) ++s;
  // At the end of the range, knots repeated more than `order` times leave
  // empty spans: the last one that is not.
  while (s > order - 1 && k[size_t(s)] == k[size_t(s + 1)]) --s;
  return s;
}

// The degree-d basis functions that do not vanish on span s, N[r] for the
// function s - d + r (The NURBS Book, A2.2).
void basis(const std::vector<float>& k, int s, int d, double t, double* N) {
  double left[32], right[32];
  N[0] = 1.0;
  for (int j = 1; j <= d; ++j) {
    left[j] = t - double(k[size_t(s + 1 - j)]);
    right[j] = double(k[size_t(s + j)]) - t;
    double saved = 0.0;
    for (int r = 0; r < j; ++r) {
      const double den = right[r + 1] + left[j - r];
      const double q = den != 0.0 ? N[r] / den : 0.0;  // repeated knots: a zero term
      N[r] = saved + right[r + 1] * q;
      saved = left[j - r] * q;
    }
    N[j] = saved;
  }
}

// The degree-p functions on span s and their derivatives, from those of
// degree p - 1: N'(i, p) = p N(i, p-1) / (k[i+p] - k[i]) - p N(i+1, p-1) /
// (k[i+p+1] - k[i+1]) (The NURBS Book, eq. 2.7).
void basis_and_derivative(const std::vector<float>& k, int s, int p, double t, double* N, double* dN) {
  basis(k, s, p, t, N);
  if (p == 0) {
    dN[0] = 0.0;
    return;
  }
  double M[32];
  basis(k, s, p - 1, t, M);  // M[q]: the function s - p + 1 + q
  for (int r = 0; r <= p; ++r) {
    const int i = s - p + r;
    const double a = r >= 1 ? M[r - 1] : 0.0, b = r < p ? M[r] : 0.0;
    const double da = double(k[size_t(i + p)]) - double(k[size_t(i)]);
    const double db = double(k[size_t(i + p + 1)]) - double(k[size_t(i + 1)]);
    dN[r] = double(p) * ((da != 0.0 ? a / da : 0.0) - (db != 0.0 ? b / db : 0.0));
  }
}

}  // namespace

std::string nurbs_problem(const NurbsSurface& s) {
  auto axis = [](const char* name, int n, int order, const std::vector<float>& k, float t0, float t1) -> std::string {
    const std::string a(name);
    if (order < 1 || order > 20) return "\"" + a + "order\" must lie in [1, 20], not " + std::to_string(order);
    if (n < order)
      return "\"n" + a + "\" (" + std::to_string(n) + " control points) must be at least the order (" +
             std::to_string(order) + ")";
    if (int(k.size()) != n + order)
      return "\"" + a + "knots\" has " + std::to_string(k.size()) + " values, expected n" + a + " + " + a + "order = " +
             std::to_string(n + order);
    for (size_t i = 0; i + 1 < k.size(); ++i)
      if (!std::isfinite(k[i]) || !std::isfinite(k[i + 1]) || k[i + 1] < k[i])
        return "\"" + a + "knots\" must be finite and non-decreasing (value " + std::to_string(i + 1) + " is not)";
    const float lo = k[size_t(order - 1)], hi = k[size_t(n)];
    if (!(lo < hi)) return "\"" + a + "knots\" leave no span between knot " + std::to_string(order - 1) + " and knot " + std::to_string(n);
    if (!(t0 >= lo && t1 <= hi && t0 < t1))
      return "\"" + a + "0\" and \"" + a + "1\" (" + std::to_string(t0) + ", " + std::to_string(t1) +
             ") must be increasing and within the knots' range [" + std::to_string(lo) + ", " + std::to_string(hi) + "]";
    return {};
  };
  if (std::string p = axis("u", s.nu, s.uorder, s.uknots, s.u0, s.u1); !p.empty()) return p;
  if (std::string p = axis("v", s.nv, s.vorder, s.vknots, s.v0, s.v1); !p.empty()) return p;
  if (s.points.size() != size_t(s.nu) * size_t(s.nv))
    return "expected nu x nv = " + std::to_string(size_t(s.nu) * size_t(s.nv)) + " control points, given " +
           std::to_string(s.points.size());
  for (const glm::vec4& p : s.points)
    if (!(p.w > 0.f) || !std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z) || !std::isfinite(p.w))
      return "control points must be finite with weights above 0";
  return {};
}

NurbsPoint evaluate_nurbs(const NurbsSurface& s, double u, double v) {
  u = std::clamp(u, double(s.uknots[size_t(s.uorder - 1)]), double(s.uknots[size_t(s.nu)]));
  v = std::clamp(v, double(s.vknots[size_t(s.vorder - 1)]), double(s.vknots[size_t(s.nv)]));
  const int p = s.uorder - 1, q = s.vorder - 1;
  const int su = find_span(s.uknots, s.nu, s.uorder, u), sv = find_span(s.vknots, s.nv, s.vorder, v);
  double Nu[32], dNu[32], Nv[32], dNv[32];
  basis_and_derivative(s.uknots, su, p, u, Nu, dNu);
  basis_and_derivative(s.vknots, sv, q, v, Nv, dNv);
  // The homogeneous surface A (xyz) and w, and their u and v derivatives.
  glm::dvec4 S(0.0), Su(0.0), Sv(0.0);
  for (int b = 0; b <= q; ++b)
    for (int a = 0; a <= p; ++a) {
      const glm::dvec4 P(s.points[size_t(sv - q + b) * size_t(s.nu) + size_t(su - p + a)]);
      S += Nu[a] * Nv[b] * P;
      Su += dNu[a] * Nv[b] * P;
      Sv += Nu[a] * dNv[b] * P;
    }
  const glm::dvec3 x = glm::dvec3(S) / S.w;
  NurbsPoint r;
  r.p = Vec3(x);
  r.dpdu = Vec3((glm::dvec3(Su) - Su.w * x) / S.w);
  r.dpdv = Vec3((glm::dvec3(Sv) - Sv.w * x) / S.w);
  return r;
}

TriangleMesh tessellate_nurbs(const NurbsSurface& s, int dice) {
  TriangleMesh m;
  auto at = [](float a, float b, int i, int n) { return double(a) + (double(b) - double(a)) * double(i) / double(n - 1); };
  const double eps_u = 1e-4 * (double(s.u1) - double(s.u0)), eps_v = 1e-4 * (double(s.v1) - double(s.v0));
  for (int j = 0; j < dice; ++j)
    for (int i = 0; i < dice; ++i) {
      const double u = at(s.u0, s.u1, i, dice), v = at(s.v0, s.v1, j, dice);
      const NurbsPoint e = evaluate_nurbs(s, u, v);
      Vec3 n = glm::cross(e.dpdu, e.dpdv);
      if (!(glm::length(n) > 1e-12f)) {
        // A pole or a fold: the normal of a point just inside the range.
        const NurbsPoint f = evaluate_nurbs(s, i + 1 < dice ? u + eps_u : u - eps_u, j + 1 < dice ? v + eps_v : v - eps_v);
        n = glm::cross(f.dpdu, f.dpdv);
      }
      const float len = glm::length(n);
      m.positions.push_back(e.p);
      m.normals.push_back(len > 0.f && std::isfinite(len) ? n / len : Vec3(0.f, 0.f, 1.f));
      m.uvs.emplace_back(float(u), float(v));
    }
  add_grid_triangles(m, dice, dice);
  return m;
}

}  // namespace lantern
