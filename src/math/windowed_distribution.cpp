#include "math/windowed_distribution.h"

#include <cmath>

namespace lantern {

WindowedDistribution2D::WindowedDistribution2D(const std::vector<float>& f, int nu, int nv)
    : nu_(nu), nv_(nv), f_(f), sat_(size_t(nu + 1) * size_t(nv + 1), 0.0) {
  const double cell = 1.0 / (double(nu) * double(nv));
  for (int j = 0; j < nv; ++j)
    for (int i = 0; i < nu; ++i) {
      const size_t w = size_t(nu + 1);
      sat_[size_t(j + 1) * w + size_t(i + 1)] = double(f[size_t(j) * size_t(nu) + size_t(i)]) * cell +
                                                sat_[size_t(j) * w + size_t(i + 1)] +
                                                sat_[size_t(j + 1) * w + size_t(i)] - sat_[size_t(j) * w + size_t(i)];
    }
}

double WindowedDistribution2D::sat(double u, double v) const {
  const double x = glm::clamp(u, 0.0, 1.0) * nu_, y = glm::clamp(v, 0.0, 1.0) * nv_;
  const int i = std::min(int(x), nu_ - 1), j = std::min(int(y), nv_ - 1);
  const double fx = x - i, fy = y - j;
  const size_t w = size_t(nu_ + 1);
  auto at = [&](int a, int b) { return sat_[size_t(b) * w + size_t(a)]; };
  return (1 - fy) * ((1 - fx) * at(i, j) + fx * at(i + 1, j)) + fy * ((1 - fx) * at(i, j + 1) + fx * at(i + 1, j + 1));
}

double WindowedDistribution2D::integral(Vec2 lo, Vec2 hi) const {
  if (f_.empty()) return 0.0;
  return sat(hi.x, hi.y) - sat(lo.x, hi.y) - sat(hi.x, lo.y) + sat(lo.x, lo.y);
}

float WindowedDistribution2D::value(Vec2 p) const {
  const int i = glm::clamp(int(p.x * float(nu_)), 0, nu_ - 1), j = glm::clamp(int(p.y * float(nv_)), 0, nv_ - 1);
  return f_[size_t(j) * size_t(nu_) + size_t(i)];
}

namespace {

// The x in [a, b] where the non-decreasing, piecewise-linear F (linear
// between consecutive multiples of 1/n) reaches `target`: a binary search
// over the multiples, then the linear piece.
template <class F>
double invert(F&& cdf, double a, double b, int n, double target) {
  int lo = int(std::floor(a * n)), hi = int(std::ceil(b * n));
  auto edge = [&](int k) { return glm::clamp(double(k) / n, a, b); };
  while (hi - lo > 1) {
    const int mid = (lo + hi) / 2;
    if (cdf(edge(mid)) < target)
      lo = mid;
    else
      hi = mid;
  }
  const double x0 = edge(lo), x1 = edge(hi), c0 = cdf(x0), c1 = cdf(x1);
  if (!(c1 > c0)) return x0;
  return glm::clamp(x0 + (target - c0) / (c1 - c0) * (x1 - x0), x0, x1);
}

}  // namespace

bool WindowedDistribution2D::sample(Vec2 u, Vec2 lo, Vec2 hi, Vec2* p, float* pdf) const {
  const double total = integral(lo, hi);
  if (!(total > 0.0)) return false;
  // v by the window's marginal, then u along the row v falls in.
  const double v =
      invert([&](double y) { return integral(lo, Vec2(hi.x, float(y))); }, lo.y, hi.y, nv_, double(u.y) * total);
  const int j = glm::clamp(int(v * nv_), 0, nv_ - 1);
  const size_t w = size_t(nu_ + 1);
  auto row = [&](double x) {  // integral over [0, x] of row j, per unit v
    const double fx = glm::clamp(x, 0.0, 1.0) * nu_;
    const int i = std::min(int(fx), nu_ - 1);
    const double t = fx - i;
    auto d = [&](int a) { return sat_[size_t(j + 1) * w + size_t(a)] - sat_[size_t(j) * w + size_t(a)]; };
    return (1 - t) * d(i) + t * d(i + 1);
  };
  const double r0 = row(lo.x), r1 = row(hi.x);
  if (!(r1 > r0)) return false;
  const double x = invert([&](double s) { return row(s); }, lo.x, hi.x, nu_, r0 + double(u.x) * (r1 - r0));
  *p = Vec2(float(x), float(v));
  *pdf = float(double(value(*p)) / total);
  return *pdf > 0.f;
}

float WindowedDistribution2D::pdf(Vec2 p, Vec2 lo, Vec2 hi) const {
  if (p.x < lo.x || p.y < lo.y || p.x > hi.x || p.y > hi.y) return 0.f;
  const double total = integral(lo, hi);
  return total > 0.0 ? float(double(value(p)) / total) : 0.f;
}

}  // namespace lantern
