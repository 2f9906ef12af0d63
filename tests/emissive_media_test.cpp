// Emissive media (docs/media.md, "Emissive media"): closed forms, the
// three integrators against one another, and pbrt-v4's image.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>

#include "color/cie1931.h"
#include "expect_error.h"
#include "lantern/scene.h"
#include "media_scenes.h"
#include "light/volume_light.h"
#include "medium/volume_emission.h"
#include "scene/scene.h"
#include "sanitizer.h"
#include "stat_compare.h"

namespace lantern {
namespace {

// The slab of media_scenes.h made of a medium that absorbs and emits but
// does not scatter, in front of the emitter of radiance 1, which is made
// black so that it does not reflect the slab's light back (with its
// default material it does: pbrt-v4 and Lantern both give 1.908 in red
// then). Along every camera ray the radiance is exactly
//   exp(-sigma_a d) + Le (1 - exp(-sigma_a d)),   d = 2 / cos(angle),
// close to the axis at 10 degrees of field of view. Path and bdpt (whose
// light subpaths start in the slab, and whose next-event estimation
// samples its volume) must both find it.
TEST(EmissiveMedia, AbsorbingSlabMatchesClosedForm) {
  const auto scene = load_scene_from_string(slab_scene(R"(Material "diffuse" "rgb reflectance" [ 0 0 0 ]
MakeNamedMedium "slab" "string type" "homogeneous"
    "rgb sigma_a" [ 0.5 0.5 0.5 ] "rgb sigma_s" [ 0 0 0 ] "rgb Le" [ 2 1 0.25 ])"),
                                            "slab.pbrt", {});
  // The mean over the film of exp(-sigma_a 2 / cos), by a fine sum over
  // the film of the 10-degree camera (box filter, square film).
  const double tan_half = std::tan(5.0 * kPi / 180.0);
  double T = 0.0;
  const int n = 400;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const double x = ((i + 0.5) / n * 2.0 - 1.0) * tan_half, y = ((j + 0.5) / n * 2.0 - 1.0) * tan_half;
      T += std::exp(-0.5 * 2.0 * std::sqrt(1.0 + x * x + y * y)) / double(n * n);
    }
  const double Le[3] = {2.0, 1.0, 0.25};
  for (const char* integrator : {"path", "bdpt"}) {
    const RegionStats st = render_stats(*scene, integrator, 16, 16, LANTERN_ASAN ? 16 : 64, 8, {{0, 0, 16, 16}});
    for (int c = 0; c < 3; ++c) {
      const double expected = T + Le[c] * (1.0 - T);
      EXPECT_LT(std::fabs(st.mean[0][size_t(c)] - expected), 4.5 * st.std_error[0][size_t(c)] + 1e-4)
          << integrator << " channel " << c << ": " << st.mean[0][size_t(c)] << " against " << expected;
    }
  }
}

// pbrt-v4's BlackbodySpectrum as its film records it: at 6500 K the
// colour is near white, and Y is the integral of the peak-normalised
// spectrum against y-bar (in nm); checked against a midpoint sum of
// Planck's law here.
TEST(EmissiveMedia, BlackbodyIsPbrtsPeakNormalisedSpectrum) {
  const double c = 299792458.0, h = 6.62606957e-34, kb = 1.3806488e-23;
  for (double T : {1500.0, 2200.0, 6500.0}) {
    auto planck = [&](double l) { return 1.0 / (std::pow(l, 5) * std::expm1(h * c / (l * kb * T))); };
    const double peak = planck(2.8977721e-3 / T);
    double Y = 0.0;
    for (double nm = 380.0; nm <= 780.0; nm += 0.25) Y += 0.25 * planck(nm * 1e-9) / peak * cie1931_cmf(float(nm)).y;
    EXPECT_NEAR(blackbody_peak_xyz(float(T)).y, Y, 0.01 * Y) << T << " K";
  }
  const RGB white = xyz_to_linear_srgb(blackbody_peak_xyz(6500.f));
  EXPECT_NEAR(white[0] / white[2], 1.0, 0.1);
  const BlackbodyTable table(3000.f);
  EXPECT_EQ(table.at(100.f), RGB(0.f));  // pbrt-v4's media emit above 100 K only
  const RGB exact = xyz_to_linear_srgb(blackbody_peak_xyz(2345.f)), tabled = table.at(2345.f);
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(tabled[k], exact[k], 1e-3 * std::fabs(exact[0]) + 1e-6);
}

// The glowing fog ball and the ember of perf/media/glowing-fog.pbrt.
const std::vector<Region> kRegions40 = {{11, 7, 10, 10}, {28, 17, 6, 6}, {5, 26, 15, 4}, {0, 0, 40, 30}};

TEST(EmissiveMedia, IntegratorsAgree) {
  if (LANTERN_ASAN) GTEST_SKIP() << "the Release suite runs it";
  const auto scene = load_scene(std::string(LANTERN_SOURCE_DIR) + "/perf/media/glowing-fog.pbrt");
  expect_medium_integrators_agree(*scene, kRegions40);
}

TEST(EmissiveMedia, ThreadCountsGiveTheSameBits) {
  const auto scene = load_scene(std::string(LANTERN_SOURCE_DIR) + "/perf/media/glowing-fog.pbrt");
  expect_medium_thread_invariant(*scene);
}

// pbrt-v4 (volpath, 512 spp, zsobol, the scene as shipped but for the
// sample count; region means by oiiotool --cut WxH+X+Y --printstats):
// whole image, the ball, the ember, the floor.
TEST(EmissiveMedia, MatchesPbrt) {
  if (LANTERN_ASAN) GTEST_SKIP() << "the Release suite runs it";
  const auto scene = load_scene(std::string(LANTERN_SOURCE_DIR) + "/perf/media/glowing-fog.pbrt");
  expect_matches_pbrt(*scene, 160, 120, 10, 16, 4, {{0, 0, 160, 120}, {45, 30, 40, 40}, {112, 68, 24, 24}, {20, 104, 60, 16}},
                      {{0.182380, 0.092385, 0.041288},
                       {1.105969, 0.551700, 0.224313},
                       {0.229755, 0.057465, 0.010694},
                       {0.060806, 0.035413, 0.020425}},
                      0.03);
}

TEST(EmissiveMedia, BadEmissionIsRefusedWithItsLine) {
  const std::string head = "LookAt 0 0 0 0 0 1 0 1 0\nCamera \"perspective\"\nWorldBegin\n";
  expect_load_error(head + "MakeNamedMedium \"m\" \"string type\" \"homogeneous\" \"rgb Le\" [ 1 1 1 ] \"float Lescale\" -1\n",
                    "a.pbrt", {"a.pbrt:4", "\"Le\"", "not negative"});
  expect_load_error(head + "MakeNamedMedium \"m\" \"string type\" \"uniformgrid\" \"float density\" [ 1 ] "
                           "\"float temperature\" [ 1e40 ]\n",
                    "b.pbrt", {"b.pbrt:4", "temperatures must be finite"});
  expect_load_error(head + "MakeNamedMedium \"m\" \"string type\" \"rgbgrid\" \"rgb sigma_a\" [ 1 1 1 ] "
                           "\"rgb Le\" [ 1 1 1 ] \"float Lescale\" -2\n",
                    "c.pbrt", {"c.pbrt:4", "\"Lescale\" must be finite and not negative"});
}

}  // namespace
}  // namespace lantern

namespace lantern {
namespace {

TEST(EmissiveMedia, VolumeLightsIntegrateTheirEmission) {
  expect_volume_light_integrates(*load_scene(std::string(LANTERN_SOURCE_DIR) + "/perf/media/glowing-fog.pbrt"));
}

}  // namespace
}  // namespace lantern
