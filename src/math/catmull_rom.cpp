#include "math/catmull_rom.h"

#include <algorithm>
#include <cmath>

#include "math/find_interval.h"

namespace lantern {

namespace {

// One spline segment of width w from f0 to f1 with end slopes d0, d1 (per
// unit t): its value and integral at t in [0, 1] (Hermite form).
struct Segment {
  float f0, f1, d0, d1;
  float value(float t) const {
    return f0 + t * (d0 + t * (-2.f * d0 - d1 + 3.f * (f1 - f0) + t * (d0 + d1 + 2.f * (f0 - f1))));
  }
  float integral(float t) const {
    return t *
           (f0 + t * (0.5f * d0 + t * ((-2.f * d0 - d1) / 3.f + f1 - f0 + t * (0.25f * (d0 + d1) + 0.5f * (f0 - f1)))));
  }
};

// The segment from node i to i + 1 of the spline through value(k).
template <class Value>
Segment segment(const std::vector<float>& x, int i, Value&& value) {
  const int n = int(x.size());
  const float w = x[size_t(i) + 1] - x[size_t(i)];
  Segment s{value(i), value(i + 1), 0.f, 0.f};
  s.d0 = i > 0 ? w * (s.f1 - value(i - 1)) / (x[size_t(i) + 1] - x[size_t(i) - 1]) : s.f1 - s.f0;
  s.d1 = i + 2 < n ? w * (value(i + 2) - s.f0) / (x[size_t(i) + 2] - x[size_t(i)]) : s.f1 - s.f0;
  return s;
}

}  // namespace

bool catmull_rom_weights(const std::vector<float>& nodes, float x, SplineWeights* out) {
  const int n = int(nodes.size());
  if (n < 2 || !(x >= nodes.front() && x <= nodes.back())) return false;
  const int i = find_interval(n, x, [&](int k) { return nodes[size_t(k)]; });
  const float x0 = nodes[size_t(i)], x1 = nodes[size_t(i) + 1];
  const float t = (x - x0) / (x1 - x0), t2 = t * t, t3 = t2 * t;
  // The Hermite basis on the segment; each end slope is a finite
  // difference, which spreads its basis function over two nodes.
  float* w = out->weight;
  out->offset = i - 1;
  w[0] = 0.f, w[3] = 0.f;
  w[1] = 2.f * t3 - 3.f * t2 + 1.f;
  w[2] = -2.f * t3 + 3.f * t2;
  const float h0 = t3 - 2.f * t2 + t, h1 = t3 - t2;  // the slopes' basis functions
  if (i > 0) {
    const float s = h0 * (x1 - x0) / (x1 - nodes[size_t(i) - 1]);
    w[0] -= s, w[2] += s;
  } else {
    w[1] -= h0, w[2] += h0;
  }
  if (i + 2 < n) {
    const float s = h1 * (x1 - x0) / (nodes[size_t(i) + 2] - x0);
    w[1] -= s, w[3] += s;
  } else {
    w[1] -= h1, w[2] += h1;
  }
  return true;
}

float integrate_catmull_rom(const std::vector<float>& nodes, const float* values, std::vector<float>* cdf) {
  cdf->assign(nodes.size(), 0.f);
  double sum = 0.0;
  for (size_t i = 0; i + 1 < nodes.size(); ++i) {
    const Segment s = segment(nodes, int(i), [&](int k) { return values[k]; });
    sum += double(s.integral(1.f)) * double(nodes[i + 1] - nodes[i]);
    (*cdf)[i + 1] = float(sum);
  }
  return float(sum);
}

SplineSample sample_catmull_rom_2d(const std::vector<float>& nodes1, const std::vector<float>& nodes2,
                                   const float* values, const float* cdf, float alpha, float u) {
  SplineWeights a;
  if (!catmull_rom_weights(nodes1, alpha, &a)) return {};
  const size_t n2 = nodes2.size();
  auto row_mix = [&](const float* table, int k) {
    float v = 0.f;
    for (int r = 0; r < 4; ++r)
      if (a.weight[r] != 0.f) v += a.weight[r] * table[size_t(a.offset + r) * n2 + size_t(k)];
    return v;
  };
  const float total = row_mix(cdf, int(n2) - 1);
  if (!(total > 0.f)) return {};
  const float target = u * total;
  const int i = find_interval(int(n2), target, [&](int k) { return row_mix(cdf, k); });
  const float width = nodes2[size_t(i) + 1] - nodes2[size_t(i)];
  const Segment s = segment(nodes2, i, [&](int k) { return row_mix(values, k); });
  const float mass = (target - row_mix(cdf, i)) / width;
  // Newton's method on the segment's integral, kept in a bisection
  // bracket; started where a linear density would put it.
  float t = s.f0 != s.f1 ? (s.f0 - std::sqrt(max_num(0.f, s.f0 * s.f0 + 2.f * mass * (s.f1 - s.f0)))) / (s.f0 - s.f1)
                         : (s.f0 > 0.f ? mass / s.f0 : 0.5f);
  float lo = 0.f, hi = 1.f, value = s.f0;
  for (int iter = 0; iter < 100; ++iter) {
    if (!(t >= lo && t <= hi)) t = 0.5f * (lo + hi);
    const float err = s.integral(t) - mass;
    value = s.value(t);
    if (std::fabs(err) < 1e-6f || hi - lo < 1e-6f) break;
    (err < 0.f ? lo : hi) = t;
    t -= err / value;
  }
  return {nodes2[size_t(i)] + width * t, value, value / total};
}

}  // namespace lantern
