#include "math/piecewise_linear_2d.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "math/find_interval.h"

namespace lantern {

namespace {

// The t in [0, 1] where the integral from 0 to t of the linear density
// running from a (at 0) to b (at 1) reaches `mass`; written without the
// difference a - b in a denominator, so a constant density needs no case.
float invert_linear(float a, float b, float mass) {
  const float disc = max_num(a * a + 2.f * (b - a) * mass, 0.f);
  const float den = a + std::sqrt(disc);
  return den > 0.f ? std::clamp(2.f * mass / den, 0.f, 1.f) : 0.f;
}

// The integral from 0 to t of that density.
float integrate_linear(float a, float b, float t) { return t * (a + 0.5f * t * (b - a)); }

}  // namespace

PiecewiseLinear2D::PiecewiseLinear2D(const float* values, int nx, int ny, std::vector<std::vector<float>> params,
                                     bool warp)
    : nx_(nx), ny_(ny), params_(std::move(params)) {
  if (nx < 2 || ny < 2) throw std::invalid_argument("a bilinear table needs at least 2 x 2 values");
  if (params_.size() > size_t(kMaxParams)) throw std::invalid_argument("a bilinear table takes at most 3 parameters");
  size_t slices = 1;
  strides_.assign(params_.size(), 0);
  for (size_t i = params_.size(); i-- > 0;) {
    if (params_[i].empty()) throw std::invalid_argument("a table parameter needs at least one value");
    strides_[i] = uint32_t(slices);
    slices *= params_[i].size();
  }
  const size_t n = size_t(nx) * size_t(ny);
  data_.assign(values, values + slices * n);
  if (!warp) return;

  density_scale_ = float(nx - 1) * float(ny - 1);
  marginal_.assign(slices * size_t(ny), 0.f);
  conditional_.assign(slices * n, 0.f);
  for (size_t s = 0; s < slices; ++s) {
    float* d = &data_[s * n];
    float* cond = &conditional_[s * n];
    float* marg = &marginal_[s * size_t(ny)];
    bool any = false;
    for (size_t i = 0; i < n; ++i) {
      d[i] = std::isfinite(d[i]) ? max_num(d[i], 0.f) : 0.f;
      any = any || d[i] > 0.f;
    }
    if (!any) std::fill(d, d + n, 1.f);  // nothing to follow: uniform
    // Trapezoids along each row, then along the column of row totals.
    for (int y = 0; y < ny; ++y) {
      double sum = 0.0;
      for (int x = 0; x + 1 < nx; ++x) {
        sum += 0.5 * (double(d[y * nx + x]) + double(d[y * nx + x + 1]));
        cond[y * nx + x + 1] = float(sum);
      }
    }
    double total = 0.0;
    for (int y = 0; y + 1 < ny; ++y) {
      total += 0.5 * (double(cond[y * nx + nx - 1]) + double(cond[(y + 1) * nx + nx - 1]));
      marg[y + 1] = float(total);
    }
    const float norm = float(1.0 / total);
    for (size_t i = 0; i < n; ++i) d[i] *= norm, cond[i] *= norm;
    for (int y = 0; y < ny; ++y) marg[y] *= norm;
  }
}

PiecewiseLinear2D::Blend PiecewiseLinear2D::blend(const float* param) const {
  Blend b;
  b.slice[0] = 0, b.weight[0] = 1.f, b.count = 1;
  for (size_t d = 0; d < params_.size(); ++d) {
    const std::vector<float>& v = params_[d];
    if (v.size() == 1) continue;
    const int i = find_interval(int(v.size()), param[d], [&](int k) { return v[size_t(k)]; });
    float w = (param[d] - v[size_t(i)]) / (v[size_t(i) + 1] - v[size_t(i)]);
    w = w >= 0.f ? min_num(w, 1.f) : 0.f;  // outside the range (or NaN): the nearest grid
    for (int c = 0; c < b.count; ++c) {
      b.slice[c + b.count] = b.slice[c] + uint32_t(i + 1) * strides_[d];
      b.weight[c + b.count] = b.weight[c] * w;
      b.slice[c] += uint32_t(i) * strides_[d];
      b.weight[c] *= 1.f - w;
    }
    b.count *= 2;
  }
  return b;
}

float PiecewiseLinear2D::lookup(const std::vector<float>& table, size_t per_slice, const Blend& b, size_t i) const {
  float v = 0.f;
  for (int c = 0; c < b.count; ++c) v += b.weight[c] * table[size_t(b.slice[c]) * per_slice + i];
  return v;
}

PiecewiseLinear2D::Sample PiecewiseLinear2D::sample(Vec2 u, const float* param) const {
  const Blend b = blend(param);
  const size_t n = size_t(nx_) * size_t(ny_), nx = size_t(nx_);
  u = glm::clamp(u, Vec2(1e-7f), Vec2(1.f - 1e-7f));
  // The row: the marginal's interval, then within it a linear density from
  // the row above's total to the row below's.
  const int row = find_interval(ny_, u.y, [&](int k) { return lookup(marginal_, size_t(ny_), b, size_t(k)); });
  const float r0 = lookup(conditional_, n, b, size_t(row) * nx + nx - 1);
  const float r1 = lookup(conditional_, n, b, size_t(row + 1) * nx + nx - 1);
  const float t = invert_linear(r0, r1, u.y - lookup(marginal_, size_t(ny_), b, size_t(row)));
  // The column, on the conditional CDFs interpolated to that height.
  const float target = u.x * ((1.f - t) * r0 + t * r1);
  auto cdf_at = [&](int x) {
    const size_t i = size_t(row) * nx + size_t(x);
    return (1.f - t) * lookup(conditional_, n, b, i) + t * lookup(conditional_, n, b, i + nx);
  };
  const int col = find_interval(nx_, target, cdf_at);
  const size_t i = size_t(row) * nx + size_t(col);
  const float c0 = (1.f - t) * lookup(data_, n, b, i) + t * lookup(data_, n, b, i + nx);
  const float c1 = (1.f - t) * lookup(data_, n, b, i + 1) + t * lookup(data_, n, b, i + nx + 1);
  const float s = invert_linear(c0, c1, target - cdf_at(col));
  return {Vec2((float(col) + s) / float(nx_ - 1), (float(row) + t) / float(ny_ - 1)),
          ((1.f - s) * c0 + s * c1) * density_scale_};
}

PiecewiseLinear2D::Cell PiecewiseLinear2D::cell_at(Vec2 p, const Blend& b) const {
  const size_t n = size_t(nx_) * size_t(ny_), nx = size_t(nx_);
  const float fx = std::clamp(p.x, 0.f, 1.f) * float(nx_ - 1), fy = std::clamp(p.y, 0.f, 1.f) * float(ny_ - 1);
  Cell c;
  c.col = std::min(int(fx), nx_ - 2), c.row = std::min(int(fy), ny_ - 2);
  c.s = fx - float(c.col), c.t = fy - float(c.row);
  const size_t i = size_t(c.row) * nx + size_t(c.col);
  c.c0 = (1.f - c.t) * lookup(data_, n, b, i) + c.t * lookup(data_, n, b, i + nx);
  c.c1 = (1.f - c.t) * lookup(data_, n, b, i + 1) + c.t * lookup(data_, n, b, i + nx + 1);
  return c;
}

PiecewiseLinear2D::Sample PiecewiseLinear2D::invert(Vec2 p, const float* param) const {
  const Blend b = blend(param);
  const Cell c = cell_at(p, b);
  const size_t n = size_t(nx_) * size_t(ny_), nx = size_t(nx_), i = size_t(c.row) * nx + size_t(c.col);
  const float r0 = lookup(conditional_, n, b, size_t(c.row) * nx + nx - 1);
  const float r1 = lookup(conditional_, n, b, size_t(c.row + 1) * nx + nx - 1);
  const float below = (1.f - c.t) * lookup(conditional_, n, b, i) + c.t * lookup(conditional_, n, b, i + nx);
  const float row_total = (1.f - c.t) * r0 + c.t * r1;
  Sample r;
  r.p.x = row_total > 0.f ? (below + integrate_linear(c.c0, c.c1, c.s)) / row_total : 0.f;
  r.p.y = lookup(marginal_, size_t(ny_), b, size_t(c.row)) + integrate_linear(r0, r1, c.t);
  r.pdf = ((1.f - c.s) * c.c0 + c.s * c.c1) * density_scale_;
  return r;
}

float PiecewiseLinear2D::evaluate(Vec2 p, const float* param) const {
  const Cell c = cell_at(p, blend(param));
  return ((1.f - c.s) * c.c0 + c.s * c.c1) * density_scale_;
}

size_t PiecewiseLinear2D::memory_bytes() const {
  size_t p = 0;
  for (const auto& v : params_) p += v.capacity() * sizeof(float);
  return p + (data_.capacity() + marginal_.capacity() + conditional_.capacity()) * sizeof(float);
}

}  // namespace lantern
