#include "guiding/vmf_mixture.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#include "math/frame.h"

namespace lantern {

namespace {

// The density at the mean of a lobe of concentration κ on the unit sphere,
// κ / (2π (1 - e^{-2κ})) (Fisher 1953; 1 / 4π as κ goes to 0).
float vmf_norm(float kappa) { return !(kappa > 0.f) ? kInv4Pi : kappa / (2.f * kPi * -std::expm1(-2.f * kappa)); }

// The concentration whose mean cosine to the lobe's mean is r (Banerjee
// et al. 2005, "Clustering on the Unit Hypersphere using von Mises-Fisher
// Distributions", eq. 4.4, for three dimensions).
float kappa_of_mean_cosine(float r) {
  r = std::clamp(r, 0.f, 0.9999f);
  return r * (3.f - r * r) / (1.f - r * r);
}

// e^x for x <= 0 (the E-step passes exponents less their largest), to
// about 2e-5 relative (e^x = 2^i 2^f, i = trunc(x /
// ln 2), 2^f by its series to the 7th power); below -87, e^-87. Only the
// E-step's responsibilities use it: how records are shared among lobes is
// a choice of the fit, not a density anything is divided by. Four lobes at
// a time where SSE2 is (every x86-64), one at a time elsewhere.
#if defined(__SSE2__)
inline __m128 exp_nonpositive(__m128 x) {
  const __m128 t = _mm_mul_ps(_mm_max_ps(x, _mm_set1_ps(-87.f)), _mm_set1_ps(1.44269504f));
  const __m128i i = _mm_cvttps_epi32(t);  // toward zero: f in (-1, 0]
  const __m128 f = _mm_mul_ps(_mm_sub_ps(t, _mm_cvtepi32_ps(i)), _mm_set1_ps(0.69314718f));
  __m128 p = _mm_set1_ps(1.f / 720.f);
  for (float c : {1.f / 120.f, 1.f / 24.f, 1.f / 6.f, 0.5f, 1.f, 1.f}) p = _mm_add_ps(_mm_mul_ps(p, f), _mm_set1_ps(c));
  return _mm_mul_ps(p, _mm_castsi128_ps(_mm_slli_epi32(_mm_add_epi32(i, _mm_set1_epi32(127)), 23)));
}
#else
inline float exp_nonpositive(float x) {
  const float t = std::max(x, -87.f) * 1.44269504f;
  const int i = int(t);
  const float f = (t - float(i)) * 0.69314718f;
  float p = 1.f / 720.f;
  for (float c : {1.f / 120.f, 1.f / 24.f, 1.f / 6.f, 0.5f, 1.f, 1.f}) p = p * f + c;
  return p * std::bit_cast<float>(uint32_t(i + 127) << 23);
}
#endif

}  // namespace

uint32_t VmfMixture::cell_of(const Vec3& w) {
  const float l1 = std::fabs(w.x) + std::fabs(w.y) + std::fabs(w.z);
  float u = w.x / l1, v = w.y / l1;
  if (w.z < 0.f) {  // the lower half folded over the diamond's edges
    const float fu = (1.f - std::fabs(v)) * (u >= 0.f ? 1.f : -1.f),
                fv = (1.f - std::fabs(u)) * (v >= 0.f ? 1.f : -1.f);
    u = fu, v = fv;
  }
  const auto q = [](float x) { return uint32_t(std::clamp(std::lround((x * 0.5f + 0.5f) * 65535.f), 0l, 65535l)); };
  return q(u) | q(v) << 16;
}

Vec3 VmfMixture::cell_direction(uint32_t cell) {
  const float u = float(cell & 0xFFFFu) / 65535.f * 2.f - 1.f, v = float(cell >> 16) / 65535.f * 2.f - 1.f;
  Vec3 w(u, v, 1.f - std::fabs(u) - std::fabs(v));
  if (w.z < 0.f) {
    const float x = (1.f - std::fabs(v)) * (u >= 0.f ? 1.f : -1.f), y = (1.f - std::fabs(u)) * (v >= 0.f ? 1.f : -1.f);
    w.x = x, w.y = y;
  }
  return glm::normalize(w);
}

VmfMixture::VmfMixture() : lobe_(kLobes), sum_(kLobes * kSums), row_(kLobes * kRows) {
  // Means on a spherical Fibonacci lattice (Marques et al. 2013): nearly
  // even spacing, the same for every mixture.
  constexpr float kGolden = 2.39996322972865332f;  // π (3 - √5)
  for (uint32_t j = 0; j < kLobes; ++j) {
    const float z = 1.f - (2.f * float(j) + 1.f) / float(kLobes);
    const float r = std::sqrt(std::max(0.f, 1.f - z * z)), phi = kGolden * float(j);
    lobe_[j].mean = Vec3(r * std::cos(phi), r * std::sin(phi), z);
    lobe_[j].weight = lobe_[j].e_weight = 1.f / float(kLobes);
  }
  set_norms();
}

void VmfMixture::set_norms() {
  float cdf = 0.f;
  row_.resize(size_t(kLobes) * kRows);
  const auto log_or_none = [](float c) { return c > 0.f ? std::log(c) : -std::numeric_limits<float>::infinity(); };
  const auto at = [this](Row r, uint32_t j) -> float& { return row_[size_t(r) * kLobes + j]; };
  active_ = 0;
  parallax_ = false;
  for (uint32_t j = 0; j < kLobes; ++j) {
    Lobe& l = lobe_[j];
    l.norm = vmf_norm(l.kappa);
    cdf += l.weight;
    l.cdf = cdf;
    at(kX, j) = l.mean.x, at(kY, j) = l.mean.y, at(kZ, j) = l.mean.z, at(kKappa, j) = l.kappa;
    at(kLogE, j) = log_or_none(l.e_weight * l.norm);
    if (!(l.weight > 0.f)) continue;
    const uint32_t k = active_++;
    at(kSX, k) = l.mean.x, at(kSY, k) = l.mean.y, at(kSZ, k) = l.mean.z, at(kSKappa, k) = l.kappa;
    at(kSLogC, k) = std::log(l.weight * l.norm);  // (divided by the weights' total below)
    at(kSInvDistance, k) = l.inv_distance;
    at(kSWeight, k) = l.weight;
    at(kSCdf, k) = cdf;
    parallax_ = parallax_ || l.inv_distance > 0.f;
  }
  // The density is the one draws follow, which choose a lobe by weight
  // over the weights' total (cdf's last), whatever rounding left it at.
  if (active_ > 0) {
    const float log_total = std::log(at(kSCdf, active_ - 1));
    for (uint32_t k = 0; k < active_; ++k) at(kSLogC, k) -= log_total;
  }
}

// A lobe's mean (x, y, z) re-aimed from a point o away from the pivot, as
// sampling and densities both compute it. (A point at the lobe's target
// keeps the lobe's own mean.)
inline Vec3 mean_seen_from(float x, float y, float z, float inv_distance, const Vec3& o) {
  const float X = x - o.x * inv_distance, Y = y - o.y * inv_distance, Z = z - o.z * inv_distance;
  const float len2 = X * X + Y * Y + Z * Z;
  if (!(len2 > 1e-8f)) return Vec3(x, y, z);
  const float s = 1.f / std::sqrt(len2);
  return Vec3(X * s, Y * s, Z * s);
}

void VmfMixture::means_from(const Vec3& x, float* mx, float* my, float* mz) const {
  const Vec3 o = x - pivot_;
  const float *ax = row(kSX), *ay = row(kSY), *az = row(kSZ), *inv = row(kSInvDistance);
  for (uint32_t j = 0; j < active_; ++j) {
    const Vec3 m = mean_seen_from(ax[j], ay[j], az[j], inv[j], o);
    mx[j] = m.x, my[j] = m.y, mz[j] = m.z;
  }
}

void VmfMixture::move_pivot(const Vec3& p) {
  if (p == pivot_) return;
  for (Lobe& l : lobe_) {
    const Vec3 m = l.mean - (p - pivot_) * l.inv_distance;
    const float len = glm::length(m);
    if (!(len > 1e-4f)) continue;
    l.mean = m / len;
    l.inv_distance /= len;
  }
  pivot_ = p;
  set_norms();
}

void VmfMixture::add(uint32_t cell, float energy, float inv_distance) {
  if (!(energy > 0.f)) return;  // (a record that found nothing moves no lobe)
  const Vec3 w = cell_direction(cell);
  const float *x = row(kX), *y = row(kY), *z = row(kZ), *kappa = row(kKappa), *c = row(kLogE);
  // Each lobe's exponent, less the largest: a record far from every lobe
  // still goes to the nearest, not evenly to all.
  alignas(16) std::array<float, kLobes> g;
  float most = -std::numeric_limits<float>::infinity();
  for (uint32_t j = 0; j < kLobes; ++j) {
    g[j] = kappa[j] * (x[j] * w.x + y[j] * w.y + z[j] * w.z - 1.f) + c[j];
    most = std::max(most, g[j]);
  }
  if (!(most > -std::numeric_limits<float>::infinity())) return;
#if defined(__SSE2__)
  static_assert(kLobes % 4 == 0);
  const __m128 top = _mm_set1_ps(most);
  for (uint32_t j = 0; j < kLobes; j += 4)
    _mm_store_ps(g.data() + j, exp_nonpositive(_mm_sub_ps(_mm_load_ps(g.data() + j), top)));
#else
  for (uint32_t j = 0; j < kLobes; ++j) g[j] = exp_nonpositive(g[j] - most);
#endif
  float all = 0.f;
  for (uint32_t j = 0; j < kLobes; ++j) all += g[j];
  if (!(all > 0.f)) return;
  // (lobes with less than a thousandth of a record are left out: the
  // fit's choice, and most records belong to a few lobes)
  const float share = energy / all, least = all * 1e-3f;
  for (uint32_t j = 0; j < kLobes; ++j) {
    if (!(g[j] > least)) continue;
    const float e = g[j] * share;
    FixedSum* s = &sum_[j * kSums];
    s[0].add_saturating(e);
    s[1].add_saturating(e * (w.x + 1.f));
    s[2].add_saturating(e * (w.y + 1.f));
    s[3].add_saturating(e * (w.z + 1.f));
    s[4].add_saturating(e * e);
    s[5].add_saturating(e * inv_distance);
  }
}

double VmfMixture::total() const {
  FixedSum all;
  for (uint32_t j = 0; j < kLobes; ++j) all.add_saturating(sum_[j * kSums]);
  return all.value();
}

void VmfMixture::sum_up() {
  const double all = total();
  if (!(all > 0.0)) return;
  for (uint32_t j = 0; j < kLobes; ++j) {
    Lobe& l = lobe_[j];
    const FixedSum* s = &sum_[j * kSums];
    const double e = s[0].value();
    l.weight = float(e / all);
    if (!(e > 0.0)) continue;
    const Vec3 m(float((s[1].value() - e) / e), float((s[2].value() - e) / e), float((s[3].value() - e) / e));
    const float r = glm::length(m);
    if (!(r > 0.f)) continue;
    l.mean = m / r;
    // The records' effective number, (Σ e)^2 / Σ e^2: a lobe fitted from
    // one lucky record's worth is widened, from many is not.
    const double e2 = s[4].value();
    const float n = e2 > 0.0 ? float(e * e / e2) : 1.f;
    l.kappa = std::min(kMostKappa, kappa_of_mean_cosine(r) * n / (n + kPriorRecords));
    l.inv_distance = float(s[5].value() / e);
  }
  float kept = 0.f;
  for (Lobe& l : lobe_) {
    if (l.weight < kLeastWeight) l.weight = 0.f;
    kept += l.weight;
  }
  for (Lobe& l : lobe_) l.weight /= kept;
  set_norms();
}

VmfMixture VmfMixture::refined() const {
  VmfMixture out = *this;
  std::fill(out.sum_.begin(), out.sum_.end(), FixedSum());
  for (Lobe& l : out.lobe_) l.e_weight = (1.f - kResponsibilityFloor) * l.weight + kResponsibilityFloor / float(kLobes);
  out.set_norms();
  return out;
}

float VmfMixture::sphere_pdf(const Vec3& w, const Vec3& at) const {
  alignas(16) std::array<float, kLobes> mx, my, mz;
  const float *x = row(kSX), *y = row(kSY), *z = row(kSZ), *kappa = row(kSKappa), *c = row(kSLogC);
  if (parallax_) means_from(at, mx.data(), my.data(), mz.data()), x = mx.data(), y = my.data(), z = mz.data();
  float p = 0.f;
  for (uint32_t j = 0; j < active_; ++j) {
    const float a = kappa[j] * (x[j] * w.x + y[j] * w.y + z[j] * w.z - 1.f) + c[j];
    if (a > -100.f) p += std::exp(a);  // (below, e^a is not a float)
  }
  return p;
}

Vec3 VmfMixture::sample(Vec2 u, const Vec3& at, float* pdf_out) const {
  // The lobe by u.x, and u.x reused within it (Pharr et al. 2023, sec. 2.2.2).
  // (over the lobes of weight above 0: sampled rows; a mixture with none
  // is never sampled, as its total is 0, and read_state refuses one)
  if (active_ == 0) {
    *pdf_out = 0.f;
    return Vec3(0.f, 0.f, 1.f);
  }
  const float* cdf = row(kSCdf);
  const float x = u.x * cdf[active_ - 1];
  uint32_t j = 0;
  while (j + 1 < active_ && !(x < cdf[j])) ++j;
  const float lo = j == 0 ? 0.f : cdf[j - 1];
  const float ux = std::clamp((x - lo) / row(kSWeight)[j], 0.f, 0x1.fffffep-1f);
  const float kappa = row(kSKappa)[j];
  const Vec3 mean = parallax_
                        ? mean_seen_from(row(kSX)[j], row(kSY)[j], row(kSZ)[j], row(kSInvDistance)[j], at - pivot_)
                        : Vec3(row(kSX)[j], row(kSY)[j], row(kSZ)[j]);
  // The cosine to the mean by inversion, in the form that stays exact for
  // large κ (Jakob 2012, "Numerically stable sampling of the von
  // Mises-Fisher distribution on S^2").
  const float c = std::clamp(1.f + std::log1p(ux * std::expm1(-2.f * kappa)) / kappa, -1.f, 1.f);
  const float s = std::sqrt(std::max(0.f, 1.f - c * c)), phi = 2.f * kPi * u.y;
  const Vec3 w = glm::normalize(Frame::from_z(mean).from_local(Vec3(s * std::cos(phi), s * std::sin(phi), c)));
  *pdf_out = sphere_pdf(w, at);
  return w;
}

void VmfMixture::write_state(StateWriter& out) const {
  out.put(pivot_);
  out.put_vector(lobe_);
  out.put_vector(sum_);
}

void VmfMixture::read_state(StateReader& in) {
  const Vec3 pivot = in.get<Vec3>();
  std::vector<Lobe> lobes = in.get_vector<Lobe>(kLobes);
  std::vector<FixedSum> sums = in.get_vector<FixedSum>(kLobes * kSums);
  bool fine = lobes.size() == kLobes && sums.size() == kLobes * kSums;
  float cdf = 0.f;
  for (const Lobe& l : lobes) {
    cdf += l.weight;
    fine = fine && std::fabs(glm::length(l.mean) - 1.f) < 2e-6f && l.kappa > 0.f && l.kappa <= kMostKappa &&
           l.weight >= 0.f && l.weight <= 1.f && l.e_weight >= 0.f && l.e_weight <= 1.f && l.cdf == cdf &&
           l.inv_distance >= 0.f && std::isfinite(l.inv_distance);
  }
  for (const FixedSum& s : sums) fine = fine && s.sane_total();
  fine = fine && std::fabs(cdf - 1.f) < 1e-3f;
  if (!fine) throw std::runtime_error("a guiding mixture of " + std::to_string(lobes.size()) + " lobes that cannot be");
  fine = fine && std::isfinite(pivot.x + pivot.y + pivot.z);
  if (!fine) throw std::runtime_error("a guiding mixture whose pivot is not finite");
  pivot_ = pivot;
  lobe_ = std::move(lobes);
  sum_ = std::move(sums);
  set_norms();
}

}  // namespace lantern
