// The spectral renderer's pieces: the colour spaces, the fitted
// RGB-to-spectrum table, the sampled wavelengths and the film's conversion
// back to colour, each against a closed form or a quadrature independent of
// the code under test.
#include <gtest/gtest.h>

#include <array>

#include <algorithm>
#include <cmath>

#include "color/cie1931.h"
#include "color/cie_daylight.h"
#include "color/cie_fluorescent.h"
#include "color/color_space.h"
#include "color/rgb_spectrum_fit.h"
#include "color/rgb_spectrum_table.h"
#include "color/spectrum_conversion.h"
#include "lantern/render.h"
#include "lantern/scene.h"
#include "math/rng.h"
#include "sanitizer.h"
#include "stat_compare.h"

namespace lantern {
namespace {

// Pixel (1, 1) of a render at maxdepth 1: what a camera sees directly.
std::array<double, 3> direct_colour(const Scene& scene, int spp, bool spectral) {
  RenderOptions o;
  o.spp = spp;
  o.maxdepth = 1;
  o.spectral = spectral;
  const Image img = render(scene, o).image;
  std::array<double, 3> m{};
  for (int c = 0; c < 3; ++c) m[size_t(c)] = img.at(1, 1)[c];
  return m;
}

// sRGB's matrix from its primaries and the tabulated D65 agrees with IEC
// 61966-2-1's to the table's precision, and inverts.
TEST(Spectral, SrgbMatricesFromPrimaries) {
  const ColorSpace& cs = ColorSpace::srgb();
  const double published[3][3] = {
      {0.4124564, 0.3575761, 0.1804375}, {0.2126729, 0.7151522, 0.0721750}, {0.0193339, 0.1191920, 0.9503041}};
  for (size_t i = 0; i < 3; ++i)
    for (size_t j = 0; j < 3; ++j) EXPECT_NEAR(cs.rgb_to_xyz[i][j], published[i][j], 2e-3) << i << j;
  for (size_t i = 0; i < 3; ++i)
    for (size_t j = 0; j < 3; ++j) {
      double p = 0.0;
      for (size_t k = 0; k < 3; ++k) p += cs.rgb_to_xyz[i][k] * cs.xyz_to_rgb[k][j];
      EXPECT_NEAR(p, i == j ? 1.0 : 0.0, 1e-12);
    }
  const auto white = multiply(cs.rgb_to_xyz, {1.0, 1.0, 1.0});
  for (size_t c = 0; c < 3; ++c) EXPECT_NEAR(white[c], cs.white[c], 1e-12);
  EXPECT_NE(ColorSpace::named("rec2020"), nullptr);
  EXPECT_NE(ColorSpace::named("dci-p3"), nullptr);
  EXPECT_NE(ColorSpace::named("aces2065-1"), nullptr);
  EXPECT_EQ(ColorSpace::named("adobe"), nullptr);
}

// Conversions between spaces: ACES's matrix against SMPTE ST 2065-1's
// published one, a white reflectance staying white when adapted and the
// same light keeping its XYZ when not, and the chromaticities read back.
TEST(Spectral, ColourSpaceConversions) {
  const ColorSpace& srgb = ColorSpace::srgb();
  const ColorSpace& aces = *ColorSpace::named("aces2065-1");
  const double published[3][3] = {
      {0.9525523959, 0.0, 0.0000936786}, {0.3439664498, 0.7281660966, -0.0721325464}, {0.0, 0.0, 1.0088251844}};
  // (Its white is D60's spectrum as the tabulated observer sees it, as
  // pbrt-v4's is: 3e-4 off the published matrix at most.)
  for (size_t i = 0; i < 3; ++i)
    for (size_t j = 0; j < 3; ++j) EXPECT_NEAR(aces.rgb_to_xyz[i][j], published[i][j], 5e-4) << i << j;
  const auto white = multiply(rgb_conversion(aces, srgb, true), {1.0, 1.0, 1.0});
  for (double w : white) EXPECT_NEAR(w, 1.0, 1e-9);
  const auto light = multiply(srgb.rgb_to_xyz, multiply(rgb_conversion(aces, srgb, false), {0.2, 0.5, 0.9}));
  const auto direct = multiply(aces.rgb_to_xyz, {0.2, 0.5, 0.9});
  for (size_t c = 0; c < 3; ++c) EXPECT_NEAR(light[c], direct[c], 1e-9);
  const std::array<float, 8> xy = chromaticities(*ColorSpace::named("rec2020"));
  const float expected[8] = {0.708f, 0.292f, 0.170f, 0.797f, 0.131f, 0.046f, 0.3127f, 0.3290f};
  for (size_t k = 0; k < 8; ++k) EXPECT_NEAR(xy[k], expected[k], k < 6 ? 1e-6f : 3e-4f) << k;
}

// A reflectance's spectrum from the embedded table, lit by the space's
// white and seen by the observer, has the reflectance's colour again
// (Jakob & Hanika 2019's round trip), integrated at 1 nm here. The error
// is the trilinear interpolation's between the fitted nodes: about 2e-4 on
// average over the cube, largest for bright colours near grey.
TEST(Spectral, TableRoundTrip) {
  const ColorSpace& cs = ColorSpace::srgb();
  const SigmoidFitter fitter(cs);
  const RGBToSpectrumTable& table = RGBToSpectrumTable::srgb();
  EXPECT_EQ(table.resolution(), 64);
  const RGB colours[] = {RGB(0.8f, 0.4f, 0.1f),    RGB(0.1f, 0.2f, 0.7f), RGB(0.05f, 0.9f, 0.05f), RGB(0.5f),
                         RGB(0.18f, 0.18f, 0.18f), RGB(1.f, 0.f, 0.f),    RGB(0.3f, 0.6f, 0.9f)};
  for (const RGB& c : colours) {
    const SigmoidPolynomial p = table(c);
    const auto back = fitter.rgb_of({p.c0, p.c1, p.c2});
    for (int k = 0; k < 3; ++k)
      // (0.1% of the colour: of its largest channel, so that the small
      // channels of a saturated colour are held to the same absolute
      // error; plus 1e-4 for the sigmoid's tails at zero)
      EXPECT_NEAR(back[size_t(k)], c[k], 1e-4 + 1e-3 * std::max({c[0], c[1], c[2]})) << c[0] << " " << c[1] << " " << c[2];
  }
  RandomStream rng = RandomStream::make(7, 0, 0);
  double sum = 0.0;
  for (int i = 0; i < 2000; ++i) {
    const RGB c(rng.get1d(), rng.get1d(), rng.get1d());
    const SigmoidPolynomial p = table(c);
    const auto back = fitter.rgb_of({p.c0, p.c1, p.c2});
    for (int k = 0; k < 3; ++k) sum += std::fabs(back[size_t(k)] - c[k]);
    EXPECT_GE(p.max_value(), 0.f);
    EXPECT_LE(p.max_value(), 1.f);
  }
  EXPECT_LT(sum / 6000.0, 5e-4);
}

// A fit converges from zero to a saturated colour (what the table's
// continuation relies on from its first node).
TEST(Spectral, FitConverges) {
  const SigmoidFitter fitter(ColorSpace::srgb());
  const SigmoidFit f = fitter.fit({0.8, 0.4, 0.1}, {0.0, 0.0, 0.0});
  EXPECT_LT(f.residual, 1e-4);
  const auto back = fitter.rgb_of(f.c);
  EXPECT_NEAR(back[0], 0.8, 1e-5);
  EXPECT_NEAR(back[1], 0.4, 1e-5);
  EXPECT_NEAR(back[2], 0.1, 1e-5);
}

// The wavelength density integrates to 1 over 360-830 nm, and sampling it
// by inversion puts the right mass in each band.
TEST(Spectral, VisibleWavelengthSampling) {
  double integral = 0.0;
  for (int i = 0; i < 4700; ++i) integral += double(visible_wavelength_pdf(360.f + (float(i) + 0.5f) * 0.1f)) * 0.1;
  EXPECT_NEAR(integral, 1.0, 2e-4);
  EXPECT_EQ(visible_wavelength_pdf(359.f), 0.f);
  constexpr int kBands = 10, kSamples = 200000;
  int count[kBands] = {};
  for (int i = 0; i < kSamples; ++i) {
    float pdf;
    const float nm = sample_visible_wavelength((float(i) + 0.5f) / float(kSamples), &pdf);
    ASSERT_GE(nm, 359.9f);
    ASSERT_LE(nm, 830.1f);
    ASSERT_NEAR(pdf, visible_wavelength_pdf(std::clamp(nm, 360.f, 830.f)), 1e-4f * pdf);  // the closed form's
    ++count[std::min(kBands - 1, int((nm - 360.f) / 47.f))];
  }
  for (int b = 0; b < kBands; ++b) {
    double mass = 0.0;
    for (int i = 0; i < 470; ++i)
      mass += double(visible_wavelength_pdf(360.f + 47.f * float(b) + (float(i) + 0.5f) * 0.1f)) * 0.1;
    EXPECT_NEAR(double(count[b]) / kSamples, mass, 1e-3) << "band " << b;
  }
  // Four stratified wavelengths, one in each quarter of the density.
  const SampledWavelengths l = SampledWavelengths::sample_visible(0.1f);
  EXPECT_FALSE(l.is_rgb());
  for (int i = 1; i < kSpectrumSamples; ++i) EXPECT_NE(l.nm[size_t(i)], l.nm[0]);
  SampledWavelengths t = l;
  t.terminate_secondary();
  EXPECT_TRUE(t.secondary_terminated());
  EXPECT_FLOAT_EQ(t.pdf[0], l.pdf[0] / float(kSpectrumSamples));
}

// What the film records of a spectrum, averaged over sampled wavelengths,
// converges to the colour the spectrum was made from: an emitter's colour
// directly; a reflectance's under the white emitter. Monte Carlo with a
// tolerance of 5 standard errors; the RGB renderer passes colour through.
TEST(Spectral, FilmRecoversColour) {
  const RGB colours[] = {RGB(1.f), RGB(0.8f, 0.4f, 0.1f), RGB(0.1f, 0.3f, 2.5f), RGB(0.02f, 0.6f, 0.05f)};
  for (const RGB& c : colours) {
    double sum[2][3] = {}, sum2[2][3] = {};
    constexpr int n = 200000;
    for (int i = 0; i < n; ++i) {
      const SampledWavelengths l = SampledWavelengths::sample_visible((float(i) + 0.5f) / float(n));
      const RGB emitted = film_rgb(illuminant_spectrum(c, l), l);
      const RGB reflected = film_rgb(albedo_spectrum(min(c, RGB(1.f)), l) * illuminant_spectrum(RGB(1.f), l), l);
      for (int k = 0; k < 3; ++k) {
        sum[0][k] += emitted[k], sum2[0][k] += sqr(double(emitted[k]));
        sum[1][k] += reflected[k], sum2[1][k] += sqr(double(reflected[k]));
      }
    }
    for (int j = 0; j < 2; ++j)
      for (int k = 0; k < 3; ++k) {
        const double mean = sum[j][k] / n, se = std::sqrt(std::max(0.0, sum2[j][k] / n - mean * mean) / n);
        const double target = j == 0 ? c[k] : std::min(c[k], 1.f);
        EXPECT_NEAR(mean, target, 5.0 * se + 2e-3 * std::max(target, 0.1)) << (j ? "reflected " : "emitted ") << k;
      }
  }
  const SampledWavelengths rgb = SampledWavelengths::rgb();
  EXPECT_TRUE(rgb.is_rgb());
  const Spectrum s = albedo_spectrum(RGB(0.2f, 0.4f, 0.6f), rgb);
  EXPECT_EQ(s[0], 0.2f);
  EXPECT_EQ(s[3], 0.4f);  // the RGB renderer's fourth channel repeats green
  const RGB back = film_rgb(s, rgb);
  EXPECT_EQ(back[2], 0.6f);
}

// Unbounded spectra scale: f(k rgb) = k f(rgb), so a conversion commutes
// with a density or a light's scale.
TEST(Spectral, UnboundedConversionScales) {
  const SampledWavelengths l = SampledWavelengths::sample_visible(0.37f);
  const RGB c(0.3f, 1.7f, 0.9f);
  const Spectrum a = unbounded_spectrum(c, l), b = unbounded_spectrum(c * 4.f, l);
  for (int i = 0; i < kSpectrumSamples; ++i) EXPECT_NEAR(b[i], 4.f * a[i], 1e-5f * b[i]);
  EXPECT_TRUE(is_black(unbounded_spectrum(RGB(0.f), l)));
}

// Renders with sampled wavelengths (render_runs' seeds and spp scaling).
RegionStats spectral_stats(const Scene& scene, const char* integrator, int spp, int runs,
                           const std::vector<Region>& regions) {
  RenderOptions o;
  o.integrator = parse_integrator(integrator);
  o.spp = spp;
  o.maxdepth = 6;
  o.width = o.height = 32;
  o.spectral = true;
  return stats_of(render_runs(scene, o, runs, 1000), regions);
}

std::shared_ptr<Scene> shipped(const std::string& name) {
  return load_scene(std::string(LANTERN_SOURCE_DIR) + "/scenes/" + name);
}

const std::vector<Region> kCornellRegions = {
    {0, 0, 32, 32}, {0, 0, 8, 8}, {12, 4, 8, 8}, {4, 20, 8, 8}, {20, 20, 8, 8}};

// With sampled wavelengths the estimators still agree in the mean: bdpt
// and the light tracer (which share each sample's wavelengths between its
// eye and light subpaths) with the path tracer, and vcm (one set of
// wavelengths per wave, so merges join paths of the same wavelengths) with
// bdpt. 5 standard errors over 16 runs as in bdpt_test.cpp.
TEST(Spectral, IntegratorsAgreeOnTheCornellBox) {
  auto scene = shipped("cornell-box.pbrt");
  const RegionStats path = spectral_stats(*scene, "path", 16, 16, kCornellRegions);
  EXPECT_LT(max_z(spectral_stats(*scene, "bdpt", 16, 16, kCornellRegions), path), 5.0);
  EXPECT_LT(max_z(spectral_stats(*scene, "lt", 16, 16, kCornellRegions), path), 5.0);
  if (LANTERN_ASAN) return;  // (the Release suite runs vcm's)
  expect_means_agree(path, spectral_stats(*scene, "vcm", 16, 16, kCornellRegions), 0.01, "vcm against path");
}

// Bidirectional photon mapping, where merging is all there is: merging
// light vertices of other wavelengths would mix colours (the red wall's
// light would reach the floor's red and blue alike). With one set of
// wavelengths per wave its means match the path tracer's within 4.5
// standard errors plus 3% (the radius's blur), as in vcm_test.cpp.
TEST(Spectral, PhotonMappingKeepsColoursApart) {
  if (LANTERN_ASAN) GTEST_SKIP() << "the Release suite runs it";
  auto scene = shipped("cornell-box.pbrt");
  const std::vector<Region> regions = {{0, 0, 32, 32}, {8, 20, 16, 10}, {2, 8, 8, 16}, {22, 8, 8, 16}};
  const RegionStats path = spectral_stats(*scene, "path", 16, 8, regions);
  RenderOptions o;
  o.integrator = Integrator::Bpm;
  o.width = o.height = 32;
  o.spp = 16;
  o.maxdepth = 6;
  o.vcm_radius = 10.f;
  o.spectral = true;
  expect_means_agree(path, stats_of(render_runs(*scene, o, 8, 1000), regions), 0.03, "bpm against path");
}

// A grey furnace is the same in both renderers (a constant reflectance is
// a constant spectrum, the white light's spectrum comes back white): the
// closed form L (1 + rho + ... + rho^d).
TEST(Spectral, GreyFurnaceMatchesTheClosedForm) {
  const auto scene = load_scene_from_string(R"(
Film "rgb" "integer xresolution" 24 "integer yresolution" 24
LookAt 0 0 0  0 0 1  0 1 0
Camera "perspective" "float fov" 60
WorldBegin
Material "diffuse" "rgb reflectance" [0.6 0.6 0.6]
AreaLightSource "diffuse" "rgb L" [2 2 2]
ReverseOrientation
Shape "sphere" "float radius" 1
)",
                                            "furnace.pbrt");
  RenderOptions o;
  o.spp = 64;
  o.maxdepth = 3;
  o.spectral = true;
  const Image img = render(*scene, o).image;
  const double expected = 2.0 * (1.0 + 0.6 + 0.36 + 0.216);
  for (int c = 0; c < 3; ++c) {
    double sum = 0.0;
    for (int y = 0; y < img.height; ++y)
      for (int x = 0; x < img.width; ++x) sum += img.at(x, y)[c];
    // The wavelengths' noise: each pixel's 64 samples of a white spectrum.
    EXPECT_NEAR(sum / double(img.width * img.height), expected, 0.01 * expected) << "channel " << c;
  }
}

// Every kind of light given as a spectrum (a 3000 K black body) keeps its
// brightness and colour when rendered with the spectrum itself: on a grey
// floor (a grey reflects every wavelength alike) the spectral render's
// mean matches the RGB render's within 1.5% per channel, the noise of the
// wavelengths at 64 samples. A light scaled by its spectrum's luminance
// in one place and not another would be off by the spectrum's whole
// normalisation (a factor of several).
TEST(Spectral, LightsGivenAsSpectraKeepTheirBrightness) {
  const char* lights[] = {
      R"(LightSource "point" "point3 from" [0 2 0] "blackbody I" 3000 "float scale" 5)",
      R"(LightSource "spot" "point3 from" [0 2 0] "point3 to" [0 0 0] "float coneangle" 60 "blackbody I" 3000 "float scale" 5)",
      R"(LightSource "distant" "point3 from" [0 1 0] "point3 to" [0 0 0] "blackbody L" 3000)",
      R"(LightSource "infinite" "blackbody L" 3000)",
      R"(AttributeBegin
  AreaLightSource "diffuse" "blackbody L" 3000 "float power" 20
  Translate 0 2 0
  Rotate 90 1 0 0
  Shape "disk" "float radius" 0.5
AttributeEnd)"};
  for (const char* light : lights) {
    const auto scene = load_scene_from_string(std::string(R"(
LookAt 0 3 -3  0 0 0  0 1 0
Camera "perspective" "float fov" 50
Film "rgb" "integer xresolution" 24 "integer yresolution" 24
WorldBegin
)") + light + R"(
Material "diffuse" "rgb reflectance" [0.5 0.5 0.5]
Shape "trianglemesh" "point3 P" [-3 0 -3  3 0 -3  3 0 3  -3 0 3] "integer indices" [0 1 2 0 2 3]
)",
                                              "spectral-light.pbrt");
    RenderOptions o;
    o.spp = 64;
    o.maxdepth = 1;
    double mean[2][3] = {};
    for (int spectral = 0; spectral < 2; ++spectral) {
      o.spectral = spectral != 0;
      const Image img = render(*scene, o).image;
      for (int y = 0; y < img.height; ++y)
        for (int x = 0; x < img.width; ++x)
          for (int c = 0; c < 3; ++c) mean[spectral][c] += img.at(x, y)[c] / double(img.width * img.height);
    }
    for (int c = 0; c < 3; ++c) {
      EXPECT_GT(mean[0][c], 0.0) << light;
      EXPECT_NEAR(mean[1][c], mean[0][c], 0.015 * mean[0][c]) << light << ", channel " << c;
    }
  }
}

// pbrt-v4's named illuminants as light spectra: stdillum-A is Planck's law
// at 2856 K (CIE's formula: 2848 K with the older radiation constant),
// stdillum-D65 the sRGB white; each normalised like any light, the same
// in RGB and with sampled wavelengths.
TEST(Spectral, NamedIlluminantsAreLightSpectra) {
  auto sky = [](const std::string& L, bool spectral) {
    const auto scene = load_scene_from_string(R"(
LookAt 0 0 0  0 0 1  0 1 0
Camera "perspective" "float fov" 30
Film "rgb" "integer xresolution" 4 "integer yresolution" 4
WorldBegin
LightSource "infinite" )" + L + "\n",
                                              "illuminant.pbrt");
    return direct_colour(*scene, 256, spectral);
  };
  const auto a = sky(R"("spectrum L" "stdillum-A")", false), bb = sky(R"("blackbody L" 2856)", false);
  const auto d65 = sky(R"("spectrum L" "stdillum-D65")", false);
  for (size_t c = 0; c < 3; ++c) {
    EXPECT_NEAR(a[c], bb[c], 0.005 * bb[c]) << c;
    EXPECT_NEAR(d65[c], d65[1], 0.01 * d65[1]) << c;  // white
  }
  EXPECT_LT(a[2], 0.5 * a[0]);  // and A is not white
  const auto a_spectral = sky(R"("spectrum L" "stdillum-A")", true);
  for (size_t c = 0; c < 3; ++c) EXPECT_NEAR(a_spectral[c], a[c], 0.02 * a[c]) << c;
  // A fluorescent lamp: its light's colour is its chromaticity's.
  const auto f4 = sky(R"("spectrum L" "stdillum-F4")", false);
  EXPECT_GT(f4[0], 1.3f * f4[2]);  // F4, warm white, 2940 K
  const auto f4_spectral = sky(R"("spectrum L" "stdillum-F4")", true);
  for (size_t c = 0; c < 3; ++c) EXPECT_NEAR(f4_spectral[c], f4[c], 0.03 * f4[c]) << c;
  EXPECT_THROW(sky(R"("spectrum L" "stdillum-F13")", false), InputError);
}

// The fluorescent illuminants' table against the chromaticities CIE
// 015:2004 publishes for them (Table T.8, 2-degree observer, four
// decimals): a transposed column, a row out of place or a wrong entry
// moves them. Integrated at 1 nm over the table's linear interpolation,
// where the CIE summed at 5 nm, so 0.0015 of slack.
TEST(Spectral, FluorescentIlluminantsHaveThePublishedChromaticities) {
  const double published[12][2] = {{0.3131, 0.3373}, {0.3721, 0.3751}, {0.4091, 0.3941}, {0.4402, 0.4031},
                                   {0.3138, 0.3452}, {0.3779, 0.3882}, {0.3129, 0.3292}, {0.3458, 0.3586},
                                   {0.3741, 0.3727}, {0.3458, 0.3588}, {0.3805, 0.3769}, {0.4370, 0.4042}};
  for (int n = 1; n <= 12; ++n) {
    double X = 0, Y = 0, Z = 0;
    for (int nm = 380; nm <= 780; ++nm) {
      const double s = cie_fluorescent(n, float(nm));
      const Vec3 cmf = cie1931_cmf(float(nm));
      X += s * cmf.x;
      Y += s * cmf.y;
      Z += s * cmf.z;
    }
    EXPECT_NEAR(X / (X + Y + Z), published[n - 1][0], 0.0015) << "F" << n;
    EXPECT_NEAR(Y / (X + Y + Z), published[n - 1][1], 0.0015) << "F" << n;
  }
  EXPECT_EQ(cie_fluorescent(0, 500.f), 0.f);
  EXPECT_EQ(cie_fluorescent(2, 379.f), 0.f);
  EXPECT_EQ(cie_fluorescent(2, 380.f), 1.18f);
  EXPECT_FLOAT_EQ(cie_fluorescent(2, 382.5f), 0.5f * (1.18f + 1.48f));
}

// An rgbgrid medium with sampled wavelengths: its samples' colours become
// spectra as a homogeneous medium's coefficients and emission do, so a
// grid of equal samples renders the homogeneous medium of that colour
// (whose Lescale carries pbrt-v4's factor for rgbgrid emission,
// kPbrtRgbGridLeFactor).
// Saturated colours, so that an RGB channel taken for a wavelength's would
// show. (pbrt-v4 against varying samples: tests/conformance/rgbgrid.pbrt.)
TEST(Spectral, RgbGridMatchesTheHomogeneousMediumOfItsColour) {
  const std::string head = R"(
LookAt 0 0 -3 0 0 0 0 1 0
Camera "perspective" "float fov" 40
Film "rgb" "integer xresolution" 24 "integer yresolution" 24
WorldBegin
LightSource "infinite" "rgb L" [0.4 0.5 0.6]
)";
  const std::string tail = R"(
MediumInterface "m" ""
Material "interface"
Shape "sphere" "float radius" 1
)";
  std::string grid = R"(MakeNamedMedium "m" "string type" "rgbgrid" "integer nx" 4 "integer ny" 4 "integer nz" 4
  "point3 p0" [-2 -2 -2] "point3 p1" [2 2 2] "float g" 0.3 "float Lescale" 0.5)";
  std::string a = " \"rgb sigma_a\" [", sc = " \"rgb sigma_s\" [", le = " \"rgb Le\" [";
  for (int i = 0; i < 64; ++i) a += " 0.1 0.8 1.6", sc += " 1.5 0.6 0.2", le += " 0.9 0.3 0.05";
  grid += a + " ]" + sc + " ]" + le + " ]";
  // (samples 1 apart at -1.5 .. 1.5: equal over the whole unit sphere)
  const std::string homogeneous = R"(MakeNamedMedium "m" "string type" "homogeneous" "float g" 0.3 "float Lescale" 53.4284475
  "rgb sigma_a" [0.1 0.8 1.6] "rgb sigma_s" [1.5 0.6 0.2] "rgb Le" [0.9 0.3 0.05])";
  const auto as_grid = load_scene_from_string(head + grid + tail, "rgbgrid.pbrt");
  const auto as_homogeneous = load_scene_from_string(head + homogeneous + tail, "homogeneous.pbrt");
  RenderOptions o;
  o.spp = 48;
  o.spectral = true;
  o.maxdepth = 8;
  const std::vector<Region> regions = {{8, 8, 8, 8}, {4, 10, 4, 4}, {10, 3, 4, 4}, {0, 0, 4, 4}};
  for (const char* integrator : {"path", "bdpt"}) {
    o.integrator = parse_integrator(integrator);
    const RegionStats g = stats_of(render_runs(*as_grid, o, 6, 11), regions);
    const RegionStats h = stats_of(render_runs(*as_homogeneous, o, 6, 21), regions);
    max_z(h, g);
    expect_means_agree(h, g, 0.005, integrator);
  }
}

// The table fitted where it is looked up (what colours of rec2020 and
// dci-p3 are read with) gives the whole table's answers bit for bit: for
// sRGB, the table the build embeds.
TEST(Spectral, LazyTableIsTheWholeTable) {
  LazyRGBToSpectrumTable lazy(ColorSpace::srgb());
  RandomStream rng = RandomStream::make(3, 1, 2);
  for (int i = 0; i < 6; ++i) {
    const RGB c(rng.get1d(), rng.get1d(), rng.get1d());
    const SigmoidPolynomial a = lazy(c), b = RGBToSpectrumTable::srgb()(c);
    EXPECT_EQ(a.c0, b.c0) << i;
    EXPECT_EQ(a.c1, b.c1) << i;
    EXPECT_EQ(a.c2, b.c2) << i;
  }
}

// Bit-identical across thread counts with sampled wavelengths too.
TEST(Spectral, SameImageWithOneOrTwoThreads) {
  auto scene = shipped("caustics.pbrt");
  for (const char* integrator : {"path", "bdpt", "vcm"}) {
    RenderOptions o;
    o.integrator = parse_integrator(integrator);
    o.spp = 4;
    o.width = 48;
    o.height = 36;
    o.wave_size = 256;
    o.spectral = true;
    o.threads = 1;
    const Image one = render(*scene, o).image;
    o.threads = 2;
    const Image two = render(*scene, o).image;
    EXPECT_EQ(one.rgb, two.rgb) << integrator;
    o.spectral = false;
    EXPECT_NE(render(*scene, o).image.rgb, two.rgb) << integrator << ": the option must change the image";
  }
}

// CIE daylight from its three vectors: with the weights the CIE gives D65
// (M1 -0.295, M2 -0.689) it is CIE's D65 table, every 5 nm (an error in
// any entry of the three vectors would show here), and ACES's white and
// D50 have the chromaticities SMPTE ST 2065-1 and CIE 015:2004 give them,
// as the tabulated observer sees the spectra.
TEST(Spectral, DaylightMatchesCieTablesAndWhites) {
  for (int nm = 360; nm <= 830; nm += 5) {
    const double table = double(cie_d65(float(nm)));
    EXPECT_NEAR(cie_daylight(double(nm), DaylightWeights{-0.295, -0.689}), table, 1e-4 * table) << nm;
  }
  EXPECT_DOUBLE_EQ(cie_daylight(560.0, daylight_weights(kAcesWhite)), 100.0);
  auto xy = [](float (*illuminant)(float)) {
    const std::array<double, 3> xyz = illuminant_xyz(illuminant);
    const double sum = xyz[0] + xyz[1] + xyz[2];
    return std::array<double, 2>{xyz[0] / sum, xyz[1] / sum};
  };
  const auto aces = xy(aces_d60), d50 = xy(cie_d50);
  EXPECT_NEAR(aces[0], 0.32168, 3e-4);
  EXPECT_NEAR(aces[1], 0.33767, 3e-4);
  EXPECT_NEAR(d50[0], 0.34567, 3e-4);
  EXPECT_NEAR(d50[1], 0.35850, 3e-4);
  // The space's white is its spectrum's.
  EXPECT_EQ(ColorSpace::named("aces2065-1")->illuminant, &aces_d60);
}

// Colours of aces2065-1 with --spectral: a reflectance becomes the
// spectrum ACES's own table would hold (fitted under its D60 white), so a
// green outside sRGB's gamut keeps its negative red, near the matrices'
// adapted conversion; a white light of ACES is D60's spectrum, whose sRGB
// colour is the matrices' conversion of D60's XYZ, unadapted, as is
// "spectrum L" "illum-acesD60". The RGB
// renderer clamps the green into sRGB's gamut.
TEST(Spectral, AcesColoursKeepTheirGamutAndWhite) {
  auto plane = [](const std::string& reflectance, bool spectral, const std::string& L = R"("rgb L" [ 1 1 1 ])") {
    const auto scene = load_scene_from_string(R"(
LookAt 0 0 5  0 0 0  0 1 0
Camera "orthographic" "float screenwindow" [-1 1 -1 1]
Film "rgb" "integer xresolution" 4 "integer yresolution" 4
ColorSpace "aces2065-1"
WorldBegin
LightSource "infinite" )" + L + R"(
Material "diffuse" "rgb reflectance" [ )" + reflectance + R"( ]
Shape "trianglemesh" "point3 P" [-3 -3 0  3 -3 0  3 3 0  -3 3 0] "integer indices" [0 1 2 0 2 3]
)",
                                              "aces.pbrt");
    return direct_colour(*scene, 64, spectral);
  };
  const ColorSpace& aces = *ColorSpace::named("aces2065-1");
  const ColorSpace& srgb = ColorSpace::srgb();
  // A diffuse plane under a uniform sky of radiance L reflects L times its
  // reflectance (maxdepth 1), seen straight on.
  const auto adapted = multiply(rgb_conversion(aces, srgb, true), {0.1, 0.5, 0.1});
  const auto white_light = multiply(rgb_conversion(aces, srgb, false), {1.0, 1.0, 1.0});
  const auto spectral_green = plane("0.1 0.5 0.1", true), rgb_green = plane("0.1 0.5 0.1", false);
  const auto spectral_grey = plane("0.5 0.5 0.5", true);
  // pbrt-v4's named spectrum of that white, a light's spectrum (luminance 1).
  const auto named_grey = plane("0.5 0.5 0.5", true, R"("spectrum L" "illum-acesD60")");
  ASSERT_LT(adapted[0], -0.2);
  for (size_t c = 0; c < 3; ++c) {
    // Green: the fitted spectrum under D60's light, a few hundredths from
    // the adapted matrices (the spectrum is not the matrices' adaptation).
    EXPECT_NEAR(spectral_green[c] / white_light[c], adapted[c], 0.04) << c;
    // Grey: half of D60 in sRGB.
    EXPECT_NEAR(spectral_grey[c], 0.5 * white_light[c], 0.005 * white_light[c]) << c;
    EXPECT_NEAR(named_grey[c], 0.5 * white_light[c], 0.005 * white_light[c]) << c;
  }
  EXPECT_LT(spectral_green[0], -0.2);
  EXPECT_GE(rgb_green[0], 0.0);
}

}  // namespace
}  // namespace lantern
