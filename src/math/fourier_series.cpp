#include "math/fourier_series.h"

#include <cmath>

#include "math/common.h"

namespace lantern {

float fourier(const float* a, int m, double cos_phi) {
  double sum = 0.0, prev = cos_phi, cur = 1.0;  // cos(-phi), cos(0)
  for (int k = 0; k < m; ++k) {
    sum += double(a[k]) * cur;
    const double next = 2.0 * cos_phi * cur - prev;
    prev = cur, cur = next;
  }
  return float(sum);
}

FourierSample sample_fourier(const float* a, int m, float u) {
  // The series is even: choose the half circle by u's first half, and
  // invert within [0, pi] with what remains of u.
  const bool mirror = u >= 0.5f;
  u = mirror ? 2.f * (1.f - u) : 2.f * u;
  double lo = 0.0, hi = kPi, phi = 0.5 * kPi, f = a[0];
  for (int iter = 0; iter < 100; ++iter) {
    const double c = std::cos(phi), s = std::sqrt(max_num(0.0, 1.0 - c * c));
    double F = double(a[0]) * phi;
    f = a[0];
    double cos_prev = c, cos_cur = 1.0, sin_prev = -s, sin_cur = 0.0;
    for (int k = 1; k < m; ++k) {
      const double sin_next = 2.0 * c * sin_cur - sin_prev, cos_next = 2.0 * c * cos_cur - cos_prev;
      sin_prev = sin_cur, sin_cur = sin_next, cos_prev = cos_cur, cos_cur = cos_next;
      F += double(a[k]) * sin_next / double(k);
      f += double(a[k]) * cos_next;
    }
    F -= double(u) * double(a[0]) * kPi;
    (F > 0.0 ? hi : lo) = phi;
    if (std::fabs(F) < 1e-6 || hi - lo < 1e-6) break;
    phi -= F / f;
    if (!(phi > lo && phi < hi)) phi = 0.5 * (lo + hi);
  }
  FourierSample r;
  r.phi = float(mirror ? 2.0 * kPi - phi : phi);
  r.value = float(f);
  r.pdf = a[0] > 0.f ? float(f / (2.0 * kPi * double(a[0]))) : 0.f;
  return r;
}

}  // namespace lantern
