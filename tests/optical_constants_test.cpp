// D65, the reduction of reflectance spectra to sRGB, conductor Fresnel and
// the fit of named metals to per-channel (eta, k), against closed forms and
// published figures.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "color/cie1931.h"
#include "color/optical_constants.h"
#include "lantern/scene.h"
#include "sanitizer.h"
#include "scene/pbrt/params.h"
#include "stat_compare.h"

namespace lantern {
namespace {

// D65 seen by the 1931 observer has chromaticity (0.31272, 0.32903)
// (CIE 015:2004, Table T.3); a mistyped entry of either table moves it.
TEST(OpticalConstants, D65WhitePoint) {
  double xyz[3] = {0.0, 0.0, 0.0};
  for (int nm = 380; nm <= 780; ++nm)
    for (int c = 0; c < 3; ++c) xyz[c] += double(cie_d65(float(nm))) * double(cie1931_cmf(float(nm))[c]);
  const double s = xyz[0] + xyz[1] + xyz[2];
  EXPECT_NEAR(xyz[0] / s, 0.31272, 2e-4);
  EXPECT_NEAR(xyz[1] / s, 0.32903, 2e-4);
  EXPECT_FLOAT_EQ(cie_d65(560.f), 100.f);
  EXPECT_EQ(cie_d65(300.f), 0.f);
}

TEST(OpticalConstants, ReflectanceToRGB) {
  // Constants map to themselves; a spectrum reflecting only long
  // wavelengths is red; reflectance is linear.
  const RGB half = reflectance_rgb([](double) { return 0.5; });
  EXPECT_NEAR(half[0], 0.5f, 1e-6f);
  EXPECT_NEAR(half[1], 0.5f, 1e-6f);
  EXPECT_NEAR(half[2], 0.5f, 1e-6f);
  const RGB red = reflectance_rgb([](double nm) { return nm > 600.0 ? 1.0 : 0.0; });
  EXPECT_GT(red[0], 0.5f);
  EXPECT_LT(red[2], 0.05f);
  const RGB rest = reflectance_rgb([](double nm) { return nm > 600.0 ? 0.0 : 1.0; });
  EXPECT_NEAR(red[0] + rest[0], 1.f, 1e-5f);
  EXPECT_NEAR(red[1] + rest[1], 1.f, 1e-5f);
}

TEST(OpticalConstants, FresnelConductorClosedForms) {
  // Normal incidence: ((n-1)^2 + k^2) / ((n+1)^2 + k^2).
  for (auto [n, k] : {std::pair{0.2, 3.9}, std::pair{1.5, 0.0}, std::pair{2.7, 8.4}}) {
    const double expected = ((n - 1) * (n - 1) + k * k) / ((n + 1) * (n + 1) + k * k);
    EXPECT_NEAR(fresnel_conductor(1.0, n, k), expected, 1e-12);
    EXPECT_NEAR(fresnel_conductor(0.0, n, k), 1.0, 1e-9);  // grazing
  }
  // A dielectric at Brewster's angle reflects only the perpendicular part:
  // F = Rs / 2 with Rs = ((cos_i - n cos_t) / (cos_i + n cos_t))^2.
  const double n = 1.5, theta = std::atan(n);
  const double cos_i = std::cos(theta), cos_t = std::sqrt(1.0 - std::pow(std::sin(theta) / n, 2));
  const double rs = std::pow((cos_i - n * cos_t) / (cos_i + n * cos_t), 2);
  EXPECT_NEAR(fresnel_conductor(cos_i, n, 0.0), 0.5 * rs, 1e-12);
  // Hemispherical average of glass of index 1.5: 0.0918 (the diffuse
  // reflectance of a smooth dielectric, e.g. d'Eon, A Hitchhiker's Guide to
  // Multiple Scattering, 2016).
  EXPECT_NEAR(fresnel_conductor_average(1.5, 0.0), 0.0918, 5e-4);
}

// A metal whose n and k do not vary with wavelength is fitted back to
// itself in every channel.
TEST(OpticalConstants, FitRecoversAConstantMetal) {
  for (auto [n, k] : {std::pair{0.2f, 3.9f}, std::pair{1.2f, 2.4f}, std::pair{0.05f, 4.5f}, std::pair{2.8f, 8.0f}}) {
    const std::vector<OpticalConstant> table = {{300.f, n, k}, {900.f, n, k}};
    const ConductorRGB fit = fit_conductor_rgb(table);
    for (int c = 0; c < 3; ++c) {
      EXPECT_NEAR(fit.eta[c], n, 2e-3f * (1.f + n)) << n << " " << k;
      EXPECT_NEAR(fit.k[c], k, 2e-3f * k) << n << " " << k;
    }
  }
}

// Each named metal's fitted channels reproduce the measured spectra's
// normal and hemispherical reflectance (clipped below 1) in that channel.
TEST(OpticalConstants, NamedMetalsMatchTheirSpectra) {
  for (const char* metal : {"Cu", "Au", "Ag", "Al", "CuZn", "MgO", "TiO2"}) {
    const auto table = optical_constants(metal);
    ASSERT_FALSE(table.empty()) << metal;
    const auto fit = named_conductor_rgb(metal);
    ASSERT_TRUE(fit) << metal;
    auto nk = [&](double nm) {
      size_t i = 0;
      while (i + 2 < table.size() && table[i + 1].nm < nm) ++i;
      const double t = std::clamp((nm - table[i].nm) / (table[i + 1].nm - table[i].nm), 0.0, 1.0);
      return std::pair{(1 - t) * table[i].n + t * table[i + 1].n, (1 - t) * table[i].k + t * table[i + 1].k};
    };
    const RGB normal = reflectance_rgb([&](double nm) {
      auto [n, k] = nk(nm);
      return fresnel_conductor(1.0, n, k);
    });
    const RGB average = reflectance_rgb([&](double nm) {
      auto [n, k] = nk(nm);
      return fresnel_conductor_average(n, k);
    });
    for (int c = 0; c < 3; ++c) {
      EXPECT_NEAR(fresnel_conductor(1.0, fit->eta[c], fit->k[c]), std::min(double(normal[c]), 0.999), 1e-3)
          << metal << " channel " << c;
      EXPECT_NEAR(fresnel_conductor_average(fit->eta[c], fit->k[c]), std::min(double(average[c]), 0.999), 2e-3)
          << metal << " channel " << c;
    }
  }
  EXPECT_FALSE(named_conductor_rgb("Pt"));
  // The transparent crystals: their published sodium-line indices, 1.7375
  // (MgO, Stephens and Malitson) and 2.613 (rutile, ordinary ray).
  auto index_at = [](std::span<const OpticalConstant> t, float nm) {
    size_t i = 0;
    while (t[i + 1].nm < nm) ++i;
    const float a = (nm - t[i].nm) / (t[i + 1].nm - t[i].nm);
    return (1 - a) * t[i].n + a * t[i + 1].n;
  };
  EXPECT_NEAR(index_at(optical_constants("MgO"), 589.3f), 1.7375f, 1e-3f);
  EXPECT_NEAR(index_at(optical_constants("TiO2"), 589.3f), 2.613f, 2e-3f);
  EXPECT_NEAR(named_conductor_rgb("MgO")->k[1], 0.f, 1e-2f);  // to the fit's tint steps
}

// The parser's named spectra come from the fit; unknown names are refused.
TEST(OpticalConstants, NamedSpectraInScenes) {
  const auto cu = named_conductor_rgb("Cu");
  EXPECT_EQ(pbrt::named_spectrum_rgb("metal-Cu-eta"), cu->eta);
  EXPECT_EQ(pbrt::named_spectrum_rgb("metal-Cu-k"), cu->k);
  EXPECT_EQ(pbrt::named_spectrum_rgb("metal-CuZn-k"), named_conductor_rgb("CuZn")->k);
  EXPECT_FALSE(pbrt::named_spectrum_rgb("metal-Cu-n"));
  EXPECT_FALSE(pbrt::named_spectrum_rgb("metal-Pt-eta"));
  EXPECT_FALSE(pbrt::named_spectrum_rgb("metal-"));
  EXPECT_FALSE(pbrt::named_spectrum_rgb("metal--k"));
  EXPECT_EQ(pbrt::named_spectrum_rgb("glass-BK7"), RGB(1.5168f));
}

// perf/materials/named-metals.pbrt at 125x30 against pbrt-v4's region
// means (pbrt-v4 with the film set to 125x30 and 16384 spp; 4x4-pixel means
// by oiiotool --cut --printstats): the aluminium and brass spheres and the
// sky. pbrt-v4's brass is the same table (Querry 1985) rendered spectrally,
// so it checks the reduction itself; its copper, gold and silver come from
// another compilation than Lantern's and differ by the data
// (docs/materials.md).
TEST(OpticalConstants, MetalsMatchPbrt) {
  if (LANTERN_ASAN) GTEST_SKIP() << "the Release suite runs it";
  auto scene = load_scene(std::string(LANTERN_SOURCE_DIR) + "/perf/materials/named-metals.pbrt");
  const std::vector<Region> regions = {{72, 13, 4, 4}, {83, 13, 4, 4}, {0, 0, 20, 30}};
  const std::vector<std::array<double, 3>> pbrt = {
      {0.634277, 0.640198, 0.642120}, {0.620087, 0.530792, 0.289581}, {0.8, 0.8, 0.8}};
  expect_matches_pbrt(*scene, 125, 30, 6, 64, 4, regions, pbrt, 0.01);
}

}  // namespace
}  // namespace lantern
