// Media whose colours are given in colour spaces other than sRGB, with
// sampled wavelengths and in RGB: homogeneous and rgbgrid coefficients,
// and an rgbgrid's emission, against closed forms and each other.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "color/cie1931.h"
#include "color/color_space.h"
#include "color/rgb_spectrum_fit.h"
#include "lantern/render.h"
#include "lantern/scene.h"
#include "sanitizer.h"
#include "stat_compare.h"

namespace lantern {
namespace {

// A sphere of radius 1 filled with medium "m" (defined by `medium`), seen
// head-on by a 4x4 orthographic camera whose window is +-`half`; `world`
// (lights, a colour space) comes before it.
std::shared_ptr<Scene> medium_ball(const std::string& half, const std::string& world, const std::string& medium) {
  return load_scene_from_string("LookAt 0 0 -3  0 0 0  0 1 0\nCamera \"orthographic\" \"float screenwindow\" [-" + half +
                                    " " + half + " -" + half + " " + half +
                                    "]\nFilm \"rgb\" \"integer xresolution\" 4 \"integer yresolution\" 4\nWorldBegin\n" + world +
                                    "\n" + medium + "\nMediumInterface \"m\" \"\"\nMaterial \"interface\"\nShape \"sphere\" \"float radius\" 1\n",
                                "medium-ball.pbrt");
}

// A medium's coefficient of rec2020 with --spectral is the unbounded
// spectrum rec2020's own table holds for it, as pbrt-v4 makes it: the
// white sky seen through an absorbing sphere (a chord of 2 at the middle,
// no scattering) has the colour of exp(-2 sigma_a(lambda)) under D65. The
// cyan sigma_a lies outside sRGB's gamut; read through sRGB (clamped into
// it, by sRGB's table) the sky came out (0.609, 0.072, 0.054) where it is
// (0.996, 0.110, 0.068) (checked).
TEST(Spectral, MediaCoefficientsOfOtherSpacesKeepTheirSpectra) {
  // The same coefficient as a homogeneous medium's and as an rgbgrid's
  // eight samples (a grid's values are read as pbrt-v4's RGBGridMedium
  // reads them: by the space's table; the samples lie at the centres of
  // the grid's cells, 1.5 from the middle, so the sphere sees them
  // constant); in RGB, converted into sRGB and clamped into its gamut,
  // both alike. Read as sRGB values, as they were before, the grid came
  // out (0.497, 0.090, 0.057) with sampled wavelengths and (0.670, 0.091,
  // 0.061) in RGB (checked).
  std::string absorbing, clear;
  for (int i = 0; i < 8; ++i) absorbing += " 0.1 0.6 0.7", clear += " 0 0 0";
  const std::vector<std::string> media = {
      R"(MakeNamedMedium "m" "string type" "homogeneous" "rgb sigma_a" [ 0.1 0.6 0.7 ] "rgb sigma_s" [ 0 0 0 ] "float scale" 2)",
      R"(MakeNamedMedium "m" "string type" "rgbgrid" "integer nx" 2 "integer ny" 2 "integer nz" 2
  "point3 p0" [ -3 -3 -3 ] "point3 p1" [ 3 3 3 ] "rgb sigma_a" [)" +
          absorbing + R"( ] "rgb sigma_s" [)" + clear + R"( ] "float scale" 2)"};
  LazyRGBToSpectrumTable rec2020(*ColorSpace::named("rec2020"));
  const double m = 2.0 * 0.7;  // unbounded: 2m times the shape of rgb / 2m, m the largest channel
  const SigmoidPolynomial shape = rec2020(RGB(float(0.1 / m), float(0.6 / m), float(0.7 / m)));
  const RGB spectral = reflectance_rgb([&](double nm) { return std::exp(-2.0 * 2.0 * m * double(shape(float(nm)))); });
  for (const std::string& medium : media) {
    const auto scene = medium_ball("0.02", "LightSource \"infinite\" \"rgb L\" [ 1 1 1 ]\nColorSpace \"rec2020\"", medium);
    RenderOptions o;
    o.spp = 128;
    o.spectral = true;
    // (Four wavelengths a sample through a transmittance that varies 30-fold
    // over the spectrum: the mean over independent renders, with its error.)
    const RegionStats st = stats_of(render_runs(*scene, o, 8, 31), {{0, 0, 4, 4}});
    for (size_t c = 0; c < 3; ++c)
      EXPECT_NEAR(st.mean[0][c], spectral[int(c)], 4.5 * st.std_error[0][c] + 0.002 * spectral[int(c)]) << c << medium;
    // In RGB: the coefficient converted into sRGB, its negative red clamped.
    o.spectral = false;
    const Matrix3d to_srgb = rgb_conversion(*ColorSpace::named("rec2020"), ColorSpace::srgb(), true);
    const RegionStats rgb = stats_of(render_runs(*scene, o, 8, 31), {{0, 0, 4, 4}});
    for (size_t c = 0; c < 3; ++c) {
      const double k = std::max(0.0, to_srgb[c][0] * 0.1 + to_srgb[c][1] * 0.6 + to_srgb[c][2] * 0.7);
      EXPECT_NEAR(rgb.mean[0][c], std::exp(-2.0 * 2.0 * k), 4.5 * rgb.std_error[0][c] + 1e-3) << c << medium;
    }
  }
}

// An rgbgrid's Le of another colour space is that space's illuminant, as a
// homogeneous medium's Le is (pbrt-v4: RGBIlluminantSpectrum of the space,
// whose white for aces2065-1 is ACES's daylight): an absorbing ball glowing
// a saturated ACES green looks the same either way, with sampled
// wavelengths and in RGB. (The grid's Le is pbrt-v4's, 106.856895 times
// the homogeneous medium's: Lescale undoes it.) Read as sRGB values, as
// before, the grid glowed (0.171, 0.770, 0.086) with sampled wavelengths
// against the homogeneous ball's (-0.421, 0.967, -0.012), and in RGB
// (0.171, 0.770, 0.086) against (0, 0.996, 0) (checked).
TEST(Spectral, GridEmissionOfOtherSpacesIsThatSpacesIlluminant) {
  if (LANTERN_ASAN) GTEST_SKIP() << "statistics only: the Release suite runs it";
  std::string absorbing, clear, glow;
  for (int i = 0; i < 8; ++i) absorbing += " 1 1 1", clear += " 0 0 0", glow += " 0.2 0.9 0.1";
  const std::vector<std::string> media = {
      R"(MakeNamedMedium "m" "string type" "homogeneous" "rgb sigma_a" [ 1 1 1 ] "rgb sigma_s" [ 0 0 0 ] "rgb Le" [ 0.2 0.9 0.1 ])",
      R"(MakeNamedMedium "m" "string type" "rgbgrid" "integer nx" 2 "integer ny" 2 "integer nz" 2
  "point3 p0" [ -3 -3 -3 ] "point3 p1" [ 3 3 3 ] "rgb sigma_a" [)" +
          absorbing + R"( ] "rgb sigma_s" [)" + clear + R"( ] "rgb Le" [)" + glow + R"( ] "float Lescale" 0.00935830)"};
  for (bool spectral : {true, false}) {
    std::vector<RegionStats> st;
    for (const std::string& medium : media) {
      const auto scene = medium_ball("0.5", "ColorSpace \"aces2065-1\"", medium);
      RenderOptions o;
      o.spp = spectral ? 256 : 16;  // (lit by D65 instead of ACES's white, the spectral glow is 8 standard errors off)
      o.spectral = spectral;
      st.push_back(stats_of(render_runs(*scene, o, 8, 51), {{1, 1, 2, 2}}));
    }
    max_z(st[0], st[1]);
    expect_means_agree(st[0], st[1], 0.002, spectral ? "ACES glow, spectral" : "ACES glow, RGB");
  }
}

}  // namespace
}  // namespace lantern
