#include "math/distribution.h"

#include <algorithm>

namespace lantern {

Distribution1D::Distribution1D(std::vector<float> weights) : func_(std::move(weights)) {
  size_t n = func_.size();
  for (float& f : func_) f = std::isfinite(f) ? std::fabs(f) : 0.f;
  cdf_.resize(n + 1);
  cdf_[0] = 0.f;
  double acc = 0.0;
  for (size_t i = 0; i < n; ++i) {
    acc += double(func_[i]) / double(n);
    cdf_[i + 1] = float(acc);
  }
  integral_ = float(acc);
  if (integral_ == 0.f) {
    for (size_t i = 1; i <= n; ++i) cdf_[i] = float(i) / float(n);
  } else {
    for (size_t i = 1; i <= n; ++i) cdf_[i] = float(cdf_[i] / acc);
  }
  if (n > 0) cdf_[n] = 1.f;
}

size_t Distribution1D::find_interval(float u) const {
  // Largest index i with cdf_[i] <= u, clamped to a valid bucket.
  auto it = std::upper_bound(cdf_.begin(), cdf_.end(), u);
  size_t i = size_t(std::max<ptrdiff_t>(0, (it - cdf_.begin()) - 1));
  i = std::min(i, func_.size() - 1);
  // Skip zero-probability buckets that a u on their boundary could select.
  while (i + 1 < func_.size() && cdf_[i + 1] == cdf_[i]) ++i;
  return i;
}

float Distribution1D::sample_continuous(float u, float* pdf, size_t* offset) const {
  size_t i = find_interval(u);
  if (offset) *offset = i;
  float du = u - cdf_[i];
  float width = cdf_[i + 1] - cdf_[i];
  if (width > 0.f) du /= width;
  du = glm::clamp(du, 0.f, kOneMinusEpsilon);
  if (pdf) *pdf = integral_ > 0.f ? func_[i] / integral_ : 1.f;
  return std::min((float(i) + du) / float(func_.size()), kOneMinusEpsilon);
}

size_t Distribution1D::sample_discrete(float u, float* pmf, float* u_remapped) const {
  size_t i = find_interval(u);
  if (pmf) *pmf = integral_ > 0.f ? discrete_pmf(i) : 1.f / float(func_.size());
  if (u_remapped) {
    const float width = cdf_[i + 1] - cdf_[i];
    *u_remapped = width > 0.f ? glm::clamp((u - cdf_[i]) / width, 0.f, kOneMinusEpsilon) : 0.5f;
  }
  return i;
}

Distribution2D::Distribution2D(const std::vector<float>& weights, int nu, int nv) {
  conditional_.reserve(size_t(nv));
  std::vector<float> marginal(static_cast<size_t>(nv));
  for (int v = 0; v < nv; ++v) {
    std::vector<float> row(weights.begin() + size_t(v) * size_t(nu),
                           weights.begin() + size_t(v + 1) * size_t(nu));
    conditional_.emplace_back(std::move(row));
    marginal[size_t(v)] = conditional_.back().integral();
  }
  marginal_ = Distribution1D(std::move(marginal));
}

Vec2 Distribution2D::sample_continuous(Vec2 u, float* pdf) const {
  float pdf_v, pdf_u;
  size_t v;
  float d1 = marginal_.sample_continuous(u.y, &pdf_v, &v);
  float d0 = conditional_[v].sample_continuous(u.x, &pdf_u, nullptr);
  if (pdf) *pdf = pdf_u * pdf_v;
  return Vec2(d0, d1);
}

float Distribution2D::pdf(Vec2 p) const {
  int nu = int(conditional_[0].size());
  int nv = int(marginal_.size());
  int iu = glm::clamp(int(p.x * float(nu)), 0, nu - 1);
  int iv = glm::clamp(int(p.y * float(nv)), 0, nv - 1);
  if (marginal_.integral() == 0.f) return 0.f;
  return conditional_[size_t(iv)].func(size_t(iu)) / marginal_.integral();
}

}  // namespace lantern
