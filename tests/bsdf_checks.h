// Statistical checks shared by the BSDF tests: sampled directions against
// the reported pdf (chi-square over a binned sphere) and the directional
// albedo by sampling.
#pragma once

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "material/bsdf_common.h"
#include "math/rng.h"
#include "sanitizer.h"

namespace lantern::bsdf_checks {

inline Vec3 dir_from_angles(float theta_deg, float phi_deg) {
  float t = glm::radians(theta_deg), p = glm::radians(phi_deg);
  return Vec3(std::sin(t) * std::cos(p), std::sin(t) * std::sin(p), std::cos(t));
}

// Wilson-Hilferty approximation of the chi-square quantile for p = 1e-6.
inline double chi2_critical(int dof) {
  double k = dof, z = 4.75;
  double a = 1.0 - 2.0 / (9.0 * k) + z * std::sqrt(2.0 / (9.0 * k));
  return k * a * a * a;
}

// Counts of samples per bin against their expected counts: chi-square,
// with the bins expected to hold fewer than 20 pooled into one so that the
// statistic stays chi-square (and few samples where the pool expects ~0).
template <class Counts>
void expect_counts_fit(const Counts& observed, const std::vector<double>& expected, const std::string& what) {
  double chi2 = 0.0, pool_o = 0.0, pool_e = 0.0;
  int dof = 0;
  for (size_t i = 0; i < observed.size(); ++i) {
    if (expected[i] < 20.0) {
      pool_o += observed[i];
      pool_e += expected[i];
      continue;
    }
    chi2 += sqr(float(observed[i] - expected[i])) / expected[i];
    ++dof;
  }
  if (pool_e > 20.0) {
    chi2 += (pool_o - pool_e) * (pool_o - pool_e) / pool_e;
    ++dof;
  } else {
    EXPECT_LT(pool_o, 40.0 + 10.0 * pool_e) << what << ": samples where the pdf is ~0";
  }
  ASSERT_GT(dof, 1) << what;
  EXPECT_LT(chi2, chi2_critical(dof - 1)) << what << " (dof " << dof - 1 << ")";
}

template <class BSDF>
void expect_sampling_matches_pdf(const BSDF& bsdf, const Vec3& wo, TransportMode mode, const std::string& what) {
  constexpr int kTheta = 16, kPhi = 32;
  // Under the sanitizers a quarter: they check the code, the Release suite
  // the statistics (the test stays exact: expected counts follow kSamples).
  constexpr int kSamples = LANTERN_ASAN ? 100000 : 400000;
  std::vector<double> observed(kTheta * kPhi + 1, 0.0), expected(kTheta * kPhi + 1, 0.0);
  RandomStream s = RandomStream::make(7, 0, 0);
  auto bin_of = [&](const Vec3& w) {
    float theta = std::acos(glm::clamp(w.z, -1.f, 1.f));
    int bt = std::min(kTheta - 1, int(theta * kInvPi * kTheta));  // uniform in theta
    float phi = std::atan2(w.y, w.x);
    if (phi < 0.f) phi += 2.f * kPi;
    int bp = std::min(kPhi - 1, int(phi * kInv2Pi * kPhi));
    return bt * kPhi + bp;
  };
  for (int i = 0; i < kSamples; ++i) {
    float uc = s.get1d();
    Vec2 u = s.get2d();
    auto bs = bsdf.sample_f(wo, uc, u, mode);
    if (!bs || bs->pdf == 0.f) {
      observed[kTheta * kPhi] += 1;  // the "no sample" outcome
      continue;
    }
    ASSERT_FALSE(bs->specular) << what;
    observed[size_t(bin_of(bs->wi))] += 1;
  }
  // Expected counts: integrate the pdf over each bin (midpoint rule, 32x32
  // points per bin, d(omega) = sin(theta) d(theta) d(phi)).
  double total = 0.0;
  for (int bt = 0; bt < kTheta; ++bt)
    for (int bp = 0; bp < kPhi; ++bp) {
      double sum = 0.0;
      constexpr int kSub = 32;
      for (int a = 0; a < kSub; ++a)
        for (int b = 0; b < kSub; ++b) {
          float theta = kPi * (float(bt) + (a + 0.5f) / kSub) / kTheta;
          float phi = 2.f * kPi * (float(bp) + (b + 0.5f) / kSub) / kPhi;
          float r = std::sin(theta);
          sum += r * bsdf.pdf(wo, Vec3(r * std::cos(phi), r * std::sin(phi), std::cos(theta)), mode);
        }
      double cell = (kPi / kTheta) * (2.0 * kPi / kPhi) / (kSub * kSub);
      expected[size_t(bt * kPhi + bp)] = sum * cell * kSamples;
      total += sum * cell;
    }
  expected[kTheta * kPhi] = std::max(0.0, 1.0 - total) * kSamples;
  EXPECT_LT(total, 1.02) << what << ": the pdf integrates to more than 1";
  expect_counts_fit(observed, expected, what);
}

template <class BSDF>
double albedo(const BSDF& bsdf, const Vec3& wo, TransportMode mode, double* std_error) {
  RandomStream s = RandomStream::make(11, 1, 0);
  const int n = LANTERN_ASAN ? 50000 : 200000;
  double sum = 0.0, sum2 = 0.0;
  for (int i = 0; i < n; ++i) {
    float uc = s.get1d();
    Vec2 u = s.get2d();
    double v = 0.0;
    if (auto bs = bsdf.sample_f(wo, uc, u, mode); bs && bs->pdf > 0.f)
      v = double(luminance(film_rgb(bs->f, SampledWavelengths::rgb()))) * std::fabs(bs->wi.z) / bs->pdf;
    sum += v;
    sum2 += v * v;
  }
  double mean = sum / n;
  *std_error = std::sqrt(std::max(0.0, sum2 / n - mean * mean) / n);
  return mean;
}

}  // namespace lantern::bsdf_checks
