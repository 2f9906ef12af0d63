// The tabulated CIE 1931 observer and the black-body colours built on it,
// against published figures.
#include <gtest/gtest.h>

#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "color/cie1931.h"
#include "color/optical_constants.h"
#include "color/piecewise_linear_spectrum.h"
#include "expect_error.h"
#include "scene/pbrt/params.h"
#include "scene/scene.h"

namespace lantern {
namespace {

// The three functions have equal integrals (equal-energy white is
// x = y = z = 1/3), about 106.86 nm each (CIE 015); a mistyped entry of the
// table breaks the equality.
TEST(Color, ObserverTableIntegrates) {
  double sum[3] = {0.0, 0.0, 0.0};
  for (int nm = 370; nm <= 790; ++nm) {  // 1 nm steps over the linear interpolant
    const Vec3 c = cie1931_cmf(float(nm));
    for (int k = 0; k < 3; ++k) sum[k] += double(c[k]);
  }
  EXPECT_NEAR(sum[1], 106.857, 0.01);
  EXPECT_NEAR(sum[0] / sum[1], 1.0, 2e-4);
  EXPECT_NEAR(sum[2] / sum[1], 1.0, 2e-4);
  EXPECT_EQ(cie1931_cmf(379.f), Vec3(0.f));
  EXPECT_EQ(cie1931_cmf(781.f), Vec3(0.f));
  EXPECT_FLOAT_EQ(cie1931_cmf(555.f).y, 1.f);
}

// Chromaticities of black bodies: CIE illuminant A is a black body at
// 2856 K, x = 0.44757, y = 0.40745 (CIE 015); the Planckian locus passes
// (0.3451, 0.3516) at 5000 K and (0.3135, 0.3236) at 6500 K (Wyszecki and
// Stiles, Color Science, table 1(3.11)).
TEST(Color, BlackBodyChromaticities) {
  const struct {
    float kelvin, x, y;
  } known[] = {{2856.f, 0.44757f, 0.40745f}, {5000.f, 0.3451f, 0.3516f}, {6500.f, 0.3135f, 0.3236f}};
  for (const auto& k : known) {
    const Vec3 xyz = blackbody_xyz(k.kelvin);
    const float s = xyz.x + xyz.y + xyz.z;
    EXPECT_NEAR(xyz.x / s, k.x, 5e-4f) << k.kelvin;
    EXPECT_NEAR(xyz.y / s, k.y, 5e-4f) << k.kelvin;
    EXPECT_FLOAT_EQ(xyz.y, 1.f);
  }
  // In sRGB: luminance 1, warm below the D65 white point, bluish above.
  const RGB warm = pbrt::blackbody_rgb(2700.f), cold = pbrt::blackbody_rgb(12000.f);
  EXPECT_NEAR(luminance(warm), 1.f, 0.02f);
  EXPECT_GT(warm[0], warm[2]);
  EXPECT_GT(cold[2], cold[0]);
  EXPECT_EQ(pbrt::blackbody_rgb(0.f), RGB(0.f));
  EXPECT_EQ(pbrt::blackbody_rgb(-5.f), RGB(0.f));
}

// Sampled spectra: pbrt-v4's piecewise-linear interpolation, zero outside
// the samples, and the colours of spectra whose colours are known.
TEST(Color, SampledSpectra) {
  const double pairs[] = {400, 1, 500, 3, 600, 2};
  const PiecewiseLinearSpectrum s = spectrum_from_pairs(pairs);
  EXPECT_DOUBLE_EQ(s(450), 2.0);
  EXPECT_DOUBLE_EQ(s(600), 2.0);
  EXPECT_DOUBLE_EQ(s(399.9), 0.0);
  EXPECT_DOUBLE_EQ(s(600.1), 0.0);
  // A constant reflectance over the visible range is that grey.
  const double grey[] = {300, 0.35, 900, 0.35};
  const RGB g = reflectance_rgb(spectrum_from_pairs(grey));
  EXPECT_NEAR(g[0], 0.35f, 1e-5f);
  EXPECT_NEAR(g[2], 0.35f, 1e-5f);
  // Planck's law sampled every 5 nm has the black body's colour.
  std::vector<double> planck;
  for (double nm = 360; nm <= 830; nm += 5) {
    const double l = nm * 1e-9, c = 299792458.0, h = 6.62606957e-34, kb = 1.3806488e-23;
    planck.push_back(nm);
    planck.push_back(1e-13 * 2.0 * h * c * c / (std::pow(l, 5) * std::expm1(h * c / (l * kb * 4000.0))));
  }
  const RGB b = illuminant_rgb(spectrum_from_pairs(planck)), want = pbrt::blackbody_rgb(4000.f);
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(b[c], want[c], 0.003f * want[c]) << c;
  const double odd[] = {400, 1, 500};
  EXPECT_THROW(spectrum_from_pairs(odd), std::invalid_argument);
  const double falling[] = {500, 1, 400, 1};
  EXPECT_THROW(spectrum_from_pairs(falling), std::invalid_argument);
}

// Spectrum files as pbrt-v3 and pbrt-v4 read them: a conductor's eta and k
// from files give the conductor the named metal gives, and bad files and
// lists are errors naming the file and line.
TEST(Color, SpectrumFilesInScenes) {
  const auto dir = std::filesystem::temp_directory_path() / ("lantern-spd-test-" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  {
    std::ofstream eta(dir / "Au.eta.spd"), k(dir / "Au.k.spd");
    eta << "# gold\n";
    for (const OpticalConstant& row : optical_constants("Au")) {
      eta << row.nm << " " << row.n << "\n";
      k << row.nm << " " << row.k << "  # comment\n";
    }
    std::ofstream(dir / "bad.spd") << "400 0.5\n500 half\n";
  }
  // Relative to the scene file's folder, as pbrt resolves them.
  std::ofstream(dir / "gold.pbrt") << "WorldBegin\nMaterial \"conductor\" \"spectrum eta\" \"Au.eta.spd\" "
                                      "\"spectrum k\" \"Au.k.spd\"\nShape \"sphere\"\n";
  auto s = load_scene((dir / "gold.pbrt").string());
  const ConductorRGB named = *named_conductor_rgb("Au");
  const ConductorMaterial& c = s->materials.conductor.at(0);
  for (int i = 0; i < 3; ++i) {
    EXPECT_NEAR(c.eta.value[i], named.eta[i], 2e-3f * named.eta[i]) << i;
    EXPECT_NEAR(c.k.value[i], named.k[i], 2e-3f * named.k[i]) << i;
  }
  const std::string bad = (dir / "bad.spd").string();
  expect_load_error("WorldBegin\nMaterial \"diffuse\" \"spectrum reflectance\" \"" + bad + "\"\n", "b.pbrt",
                    {"b.pbrt:2", "bad.spd:2", "\"half\" is not a number"});
  expect_load_error("WorldBegin\nMaterial \"diffuse\" \"spectrum reflectance\" \"nothere.spd\"\n", "n.pbrt",
                    {"n.pbrt:2", "nothere.spd", "is neither a named spectrum", "nor a spectrum file"});
  expect_load_error("WorldBegin\nMaterial \"diffuse\" \"spectrum reflectance\" [400 0.5 500]\n", "o.pbrt",
                    {"o.pbrt:2", "odd number of values"});
  expect_load_error("WorldBegin\nMaterial \"diffuse\" \"spectrum reflectance\" [ ]\n", "e.pbrt",
                    {"e.pbrt:2", "expected a value, (wavelength, value) pairs"});
  expect_load_error("WorldBegin\nMaterial \"diffuse\" \"spectrum reflectance\" [500 0.5 400 0.5]\n", "f.pbrt",
                    {"f.pbrt:2", "wavelengths must increase"});
  expect_load_error("WorldBegin\nAreaLightSource \"diffuse\" \"blackbody L\" [4000 -1]\nShape \"sphere\"\n", "k.pbrt",
                    {"k.pbrt:2", "scale must be a finite number >= 0"});
  std::error_code ec;
  std::filesystem::remove_all(dir, ec);
}

}  // namespace
}  // namespace lantern
