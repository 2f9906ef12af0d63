// Every BSDF: sampled directions follow the reported pdf (chi-square over a
// binned sphere), no energy is created (white furnace), and the adjoint
// relation f(wo, wi) in radiance mode equals f(wi, wo) in importance mode.
#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <functional>
#include <string>

#include "bsdf_checks.h"
#include "material/bsdf_kernel.h"
#include "material/fresnel.h"
#include "math/rng.h"
#include "sanitizer.h"

namespace lantern {
namespace {
using namespace bsdf_checks;

template <class BSDF>
void expect_adjoint_reciprocity(const BSDF& bsdf, const std::string& what) {
  RandomStream s = RandomStream::make(3, 2, 0);
  int checked = 0;
  for (int i = 0; i < 2000; ++i) {
    Vec3 a = glm::normalize(Vec3(2.f * s.get1d() - 1.f, 2.f * s.get1d() - 1.f, 2.f * s.get1d() - 1.f));
    Vec3 b = glm::normalize(Vec3(2.f * s.get1d() - 1.f, 2.f * s.get1d() - 1.f, 2.f * s.get1d() - 1.f));
    Spectrum f1 = bsdf.f(a, b, TransportMode::Radiance), f2 = bsdf.f(b, a, TransportMode::Importance);
    for (int c = 0; c < 3; ++c) {
      // Relative to the value, but not below 1e-4: far in the tails of a
      // rough transmission lobe (f ~ 1e-5) the two half-vector computations
      // round differently by about 1% from one compiler to another.
      float scale = std::max({std::fabs(f1[c]), std::fabs(f2[c]), 1e-4f});
      ASSERT_NEAR(f1[c] / scale, f2[c] / scale, 1e-2f) << what << " wo=" << a.x << "," << a.y << "," << a.z << " wi=" << b.x << "," << b.y << "," << b.z << " f=" << f1[c] << " " << f2[c];
    }
    checked += !is_black(f1);
  }
  EXPECT_GT(checked, 100) << what << ": the BSDF was almost never non-zero";
}

const float kAngles[] = {5.f, 40.f, 75.f, 85.f};

TEST(BSDF, DiffuseSamplingMatchesPdf) {
  DiffuseBSDF d{Spectrum(0.5f)};
  for (float t : kAngles) expect_sampling_matches_pdf(d, dir_from_angles(t, 30.f), TransportMode::Radiance, "diffuse");
  expect_sampling_matches_pdf(d, dir_from_angles(130.f, 30.f), TransportMode::Radiance, "diffuse from below");
}

TEST(BSDF, RoughConductorSamplingMatchesPdf) {
  for (float alpha : {0.1f, 0.3f, 0.8f}) {
    ConductorBSDF c{{alpha, alpha * 0.5f}, Spectrum(0.2f, 0.9f, 1.1f, 0.9f), Spectrum(3.9f, 2.4f, 2.1f, 2.4f), Spectrum(1.f), false};
    for (float t : kAngles)
      expect_sampling_matches_pdf(c, dir_from_angles(t, 60.f), TransportMode::Radiance, "conductor a=" + std::to_string(alpha) + " theta=" + std::to_string(t));
  }
}

TEST(BSDF, RoughDielectricSamplingMatchesPdf) {
  for (float alpha : {0.1f, 0.5f})
    for (float eta : {1.5f, 1.f / 1.33f}) {
      DielectricBSDF d{{alpha, alpha}, eta};
      for (float t : {5.f, 40.f, 75.f, 130.f, 170.f})
        for (TransportMode m : {TransportMode::Radiance, TransportMode::Importance})
          expect_sampling_matches_pdf(d, dir_from_angles(t, 10.f), m,
                                      "dielectric a=" + std::to_string(alpha) + " eta=" + std::to_string(eta));
    }
}

TEST(BSDF, DiffuseTransmissionSamplingMatchesPdf) {
  for (auto [R, T] : {std::pair{Spectrum(0.6f, 0.3f, 0.2f, 0.3f), Spectrum(0.2f, 0.5f, 0.1f, 0.5f)}, std::pair{Spectrum(0.f), Spectrum(0.7f)}})
    for (float t : {5.f, 60.f, 120.f, 175.f})
      expect_sampling_matches_pdf(DiffuseTransmissionBSDF{R, T}, dir_from_angles(t, 30.f), TransportMode::Radiance,
                                  "diffuse transmission theta " + std::to_string(t));
}

// Thin glass at normal incidence: the interreflected total R' = 2R / (1 + R)
// (R = 0.04 for eta 1.5), T' = 1 - R'; every sample carries weight 1.
TEST(BSDF, ThinDielectricReflectsTheInterreflectedFresnelTotal) {
  ThinDielectricBSDF b{1.5f};
  for (Vec3 wo : {Vec3(0, 0, 1), Vec3(0, 0, -1)}) {
    RandomStream s = RandomStream::make(5, 0, 0);
    int reflected = 0;
    const int n = 200000;
    for (int i = 0; i < n; ++i) {
      auto bs = b.sample_f(wo, s.get1d(), s.get2d(), TransportMode::Radiance);
      ASSERT_TRUE(bs && bs->specular);
      EXPECT_NEAR(luminance(film_rgb(bs->f, SampledWavelengths::rgb())) * std::fabs(bs->wi.z) / bs->pdf, 1.f, 1e-5f);
      if (bs->transmission) {
        ASSERT_EQ(bs->wi, -wo);
      } else {
        ++reflected;
      }
    }
    const double r = 2.0 * 0.04 / 1.04, se = std::sqrt(r * (1 - r) / n);
    EXPECT_NEAR(double(reflected) / n, r, 4 * se);
  }
  EXPECT_NEAR(fr_dielectric(1.f, 1.5f), 0.04f, 1e-4f);
}

// The coated diffuse BSDF's samples come from random walks whose density is
// not its pdf(); tests/layered_bsdf_test.cpp checks it instead.

TEST(BSDF, WhiteFurnaceNoEnergyGain) {
  for (float t : kAngles) {
    Vec3 wo = dir_from_angles(t, 20.f);
    double se;
    double a = albedo(DiffuseBSDF{Spectrum(1.f)}, wo, TransportMode::Radiance, &se);
    EXPECT_NEAR(a, 1.0, 1e-3) << "a white Lambertian reflects everything";
    a = albedo(DiffuseTransmissionBSDF{Spectrum(0.3f), Spectrum(0.7f)}, wo, TransportMode::Radiance, &se);
    EXPECT_NEAR(a, 1.0, 4 * se + 1e-4) << "diffuse transmission, R + T = 1";
    a = albedo(DiffuseTransmissionBSDF{Spectrum(0.2f), Spectrum(0.5f)}, -wo, TransportMode::Importance, &se);
    EXPECT_NEAR(a, 0.7, 4 * se + 1e-4) << "diffuse transmission from below, R + T = 0.7";
    for (float alpha : {0.f, 0.01f, 0.2f, 0.7f}) {
      // A perfect reflector: microfacet models lose energy, never gain it.
      ConductorBSDF c{{alpha, alpha}, Spectrum(1.f), Spectrum(0.f), Spectrum(1.f), true};
      a = albedo(c, wo, TransportMode::Radiance, &se);
      EXPECT_LT(a, 1.0 + 4 * se + 1e-4) << "conductor alpha " << alpha << " theta " << t;
      if (alpha == 0.f) EXPECT_NEAR(a, 1.0, 1e-5);
      for (float eta : {1.5f, 1.f / 1.5f}) {
        DielectricBSDF d{{alpha, alpha}, eta};
        a = albedo(d, wo, TransportMode::Importance, &se);
        EXPECT_LT(a, 1.0 + 4 * se + 1e-4) << "dielectric alpha " << alpha << " eta " << eta;
        if (alpha == 0.f) EXPECT_NEAR(a, 1.0, 4 * se + 1e-3) << "smooth glass neither absorbs nor creates";
      }
      ThinDielectricBSDF thin{1.f + 3.f * alpha};
      a = albedo(thin, wo, TransportMode::Radiance, &se);
      EXPECT_NEAR(a, 1.0, 1e-4) << "thin glass neither absorbs nor creates";
      CoatedDiffuseBSDF cd{DielectricBSDF{{alpha, alpha}, 1.5f}, DiffuseBSDF{Spectrum(1.f)}, 1e-6f, Spectrum(0.f), 0.f, 100, 1};
      a = albedo(cd, wo, TransportMode::Radiance, &se);
      EXPECT_LT(a, 1.0 + 4 * se + 1e-4) << "coated diffuse alpha " << alpha;
    }
  }
}

TEST(BSDF, AdjointReciprocity) {
  expect_adjoint_reciprocity(DiffuseBSDF{Spectrum(0.7f)}, "diffuse");
  expect_adjoint_reciprocity(ConductorBSDF{{0.3f, 0.1f}, Spectrum(0.2f), Spectrum(3.f), Spectrum(1.f), false}, "conductor");
  expect_adjoint_reciprocity(DielectricBSDF{{0.3f, 0.3f}, 1.5f}, "rough dielectric");
  expect_adjoint_reciprocity(DiffuseTransmissionBSDF{Spectrum(0.6f, 0.2f, 0.1f, 0.2f), Spectrum(0.1f, 0.3f, 0.5f, 0.3f)}, "diffuse transmission");
}

TEST(Fresnel, DielectricLimits) {
  EXPECT_NEAR(fr_dielectric(1.f, 1.5f), 0.04f, 1e-4f);
  EXPECT_FLOAT_EQ(fr_dielectric(0.1f, 1.f / 1.5f), 1.f);  // total internal reflection
  EXPECT_NEAR(fr_dielectric(0.7f, 1.f), 0.f, 1e-7f);
  EXPECT_NEAR(fr_complex(1.f, 1.5f, 0.f), 0.04f, 1e-4f);
}

// The conductor's reflectance, written without complex division, against
// the textbook formula in double-precision std::complex: metals, a
// dielectric (k = 0, with total internal reflection below eta = 1), near
// index 1, and grazing and normal incidence. Taking the square root's
// other branch, or dropping the conjugate in sin^2 t, fails (checked).
TEST(Fresnel, ConductorMatchesTheComplexFormula) {
  using C = std::complex<double>;
  auto reference = [](double cos_i, double eta, double k) {
    const C e(eta, k);
    const C sin2_t = (1.0 - cos_i * cos_i) / (e * e), cos_t = std::sqrt(1.0 - sin2_t);
    const C r_parl = (e * cos_i - cos_t) / (e * cos_i + cos_t), r_perp = (cos_i - e * cos_t) / (cos_i + e * cos_t);
    return 0.5 * (std::norm(r_parl) + std::norm(r_perp));
  };
  for (const float eta : {0.05f, 0.2f, 0.5f, 0.9f, 1.f, 1.1f, 1.5f, 3.f, 10.f})
    for (const float k : {0.f, 0.01f, 0.5f, 2.f, 5.f, 10.f})
      for (int i = 0; i <= 64; ++i) {
        const float cos_i = float(i) / 64.f;
        if (cos_i == 0.f && eta == 1.f && k == 0.f) continue;  // 0 / 0 in the formula
        const double want = reference(cos_i, eta, k);
        EXPECT_NEAR(fr_complex(cos_i, eta, k), want, 2e-6 + 2e-5 * want) << cos_i << " " << eta << " " << k;
      }
  // 0 / 0 at grazing incidence on index 1: the limit of indices near 1.
  EXPECT_EQ(fr_complex(0.f, 1.f, 0.f), 1.f);
  EXPECT_EQ(fr_complex(0.5f, 0.f, 0.f), 1.f);
  // Indices near float's limits, some of whose squares overflow or
  // underflow: no NaN, in [0, 1], and the formula's value where it has one
  // (not at e = 0) except within 1e-8 of grazing on |e| past 4.3e9, which
  // reflect 1 (fr_complex's range). Without that range the small indices
  // give NaN (checked).
  for (const float eta : {0.f, 1e-20f, 1e-10f, 3e-10f, 1e-5f, 1e5f, 4e9f, 1e10f, 1.8e19f, 3e38f})
    for (const float k : {0.f, 1e-10f, 9e18f, 3e38f})
      for (const float cos_i : {0.f, 1e-9f, 0.5f, 1.f}) {
        const float r = fr_complex(cos_i, eta, k);
        EXPECT_TRUE(r >= 0.f && r <= 1.f) << r << " at " << cos_i << " " << eta << " " << k;
        const double want = reference(cos_i, eta, k);
        if (std::isfinite(want) && !(cos_i < 1e-8f && std::hypot(eta, k) > 4e9f))
          EXPECT_NEAR(r, want, 1e-6) << cos_i << " " << eta << " " << k;
      }
}

}  // namespace
}  // namespace lantern
