#include "medium/grid_density.h"

#include <algorithm>
#include <cmath>

namespace lantern {

namespace {

// a + b s, and polynomials in s up to degree 3 (c[k] multiplies s^k).
struct Linear {
  double a, b;
};
struct Cubic {
  double c[4] = {0.0, 0.0, 0.0, 0.0};
  double value(double s) const { return c[0] + s * (c[1] + s * (c[2] + s * c[3])); }
  double integral(double s) const { return s * (c[0] + s * (c[1] / 2.0 + s * (c[2] / 3.0 + s * c[3] / 4.0))); }
};

// The density along the ray inside one lattice cell, as a cubic in the
// distance s from where the ray enters it: f0 is the entry point's
// position in the cell ([0,1]^3), df its rate, c the eight samples.
Cubic cell_density(const double f0[3], const double df[3], const float c[2][2][2]) {
  Linear x[2] = {{1.0 - f0[0], -df[0]}, {f0[0], df[0]}};
  Linear y[2] = {{1.0 - f0[1], -df[1]}, {f0[1], df[1]}};
  Linear z[2] = {{1.0 - f0[2], -df[2]}, {f0[2], df[2]}};
  Cubic out;
  for (int k = 0; k < 2; ++k) {
    double quad[3] = {0.0, 0.0, 0.0};
    for (int j = 0; j < 2; ++j) {
      // along x: c[0][j][k] x0 + c[1][j][k] x1
      const double la = c[0][j][k] * x[0].a + c[1][j][k] * x[1].a, lb = c[0][j][k] * x[0].b + c[1][j][k] * x[1].b;
      quad[0] += la * y[j].a;
      quad[1] += la * y[j].b + lb * y[j].a;
      quad[2] += lb * y[j].b;
    }
    out.c[0] += quad[0] * z[k].a;
    out.c[1] += quad[0] * z[k].b + quad[1] * z[k].a;
    out.c[2] += quad[1] * z[k].b + quad[2] * z[k].a;
    out.c[3] += quad[2] * z[k].b;
  }
  return out;
}

// The s in [0, S] where the (non-decreasing) integral of p reaches r, given
// that it reaches at least r by S.
double solve_integral(const Cubic& p, double S, double r) {
  double lo = 0.0, hi = S;
  const double total = p.integral(S);
  double s = total > 0.0 ? S * r / total : 0.5 * S;
  for (int it = 0; it < 60; ++it) {
    const double f = p.integral(s) - r;
    if (f > 0.0) hi = s;
    else lo = s;
    if (std::fabs(f) <= 1e-12 * std::max(r, 1e-300) || hi - lo <= 1e-12 * S) break;
    const double rho = p.value(s);
    double next = rho > 0.0 ? s - f / rho : 0.5 * (lo + hi);
    if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
    s = next;
  }
  return std::clamp(s, 0.0, S);
}

}  // namespace

float DensityGrid::density(const Vec3& p) const {
  const Vec3 pm = Vec3(medium_from_render * Vec4(p, 1.f));
  const Vec3 u = (pm - p0) / (p1 - p0);
  if (u.x < 0.f || u.y < 0.f || u.z < 0.f || u.x > 1.f || u.y > 1.f || u.z > 1.f) return 0.f;
  const double g[3] = {double(u.x) * nx - 0.5, double(u.y) * ny - 0.5, double(u.z) * nz - 0.5};
  const int i[3] = {int(std::floor(g[0])), int(std::floor(g[1])), int(std::floor(g[2]))};
  const double f[3] = {g[0] - i[0], g[1] - i[1], g[2] - i[2]};
  double v = 0.0;
  for (int a = 0; a < 2; ++a)
    for (int b = 0; b < 2; ++b)
      for (int c = 0; c < 2; ++c)
        v += sample(i[0] + a, i[1] + b, i[2] + c) * (a ? f[0] : 1.0 - f[0]) * (b ? f[1] : 1.0 - f[1]) *
             (c ? f[2] : 1.0 - f[2]);
  return float(v);
}

float DensityGrid::integrate(const Vec3& o, const Vec3& d, float t0, float t1, float target, float* t_hit) const {
  *t_hit = kInfinity;
  const Vec3 om = Vec3(medium_from_render * Vec4(o, 1.f)), dm = glm::mat3(medium_from_render) * d;
  const int n[3] = {nx, ny, nz};
  double g0[3], dg[3];
  double ta = t0, tb = t1;
  for (int k = 0; k < 3; ++k) {  // lattice coordinates, and the box [-0.5, n - 0.5] they must stay in
    const double ext = double(p1[k]) - double(p0[k]);
    g0[k] = (double(om[k]) - p0[k]) / ext * n[k] - 0.5;
    dg[k] = double(dm[k]) / ext * n[k];
    const double lo = -0.5, hi = n[k] - 0.5;
    if (dg[k] == 0.0) {
      if (g0[k] < lo || g0[k] > hi) return 0.f;
      continue;
    }
    double ea = (lo - g0[k]) / dg[k], eb = (hi - g0[k]) / dg[k];
    if (ea > eb) std::swap(ea, eb);
    ta = std::max(ta, ea);
    tb = std::min(tb, eb);
  }
  if (!(ta < tb)) return 0.f;
  int cell[3], step[3];
  double t_next[3], t_delta[3];
  for (int k = 0; k < 3; ++k) {
    cell[k] = std::clamp(int(std::floor(g0[k] + ta * dg[k])), -1, n[k] - 1);
    step[k] = dg[k] > 0.0 ? 1 : -1;
    if (dg[k] == 0.0) {
      t_next[k] = t_delta[k] = kInfinity;
    } else {
      const double edge = dg[k] > 0.0 ? cell[k] + 1 : cell[k];
      t_next[k] = (edge - g0[k]) / dg[k];
      t_delta[k] = 1.0 / std::fabs(dg[k]);
    }
  }
  double sum = 0.0, t = ta;
  while (t < tb) {
    const int axis = t_next[0] < t_next[1] ? (t_next[0] < t_next[2] ? 0 : 2) : (t_next[1] < t_next[2] ? 1 : 2);
    const double t_exit = std::min(tb, t_next[axis]);
    float c[2][2][2];
    bool any = false;
    for (int a = 0; a < 2; ++a)
      for (int b = 0; b < 2; ++b)
        for (int e = 0; e < 2; ++e) any |= (c[a][b][e] = sample(cell[0] + a, cell[1] + b, cell[2] + e)) != 0.f;
    if (any && t_exit > t) {
      const double f0[3] = {g0[0] + t * dg[0] - cell[0], g0[1] + t * dg[1] - cell[1], g0[2] + t * dg[2] - cell[2]};
      const Cubic p = cell_density(f0, dg, c);
      const double S = t_exit - t, I = std::max(0.0, p.integral(S));
      if (target >= 0.f && sum + I >= target) {
        *t_hit = float(t + solve_integral(p, S, double(target) - sum));
        return target;
      }
      sum += I;
    }
    if (t_exit >= tb) break;
    cell[axis] += step[axis];
    if (cell[axis] < -1 || cell[axis] > n[axis] - 1) break;
    t_next[axis] += t_delta[axis];
    t = t_exit;
  }
  return float(sum);
}

}  // namespace lantern
