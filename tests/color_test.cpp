// The tabulated CIE 1931 observer and the black-body colours built on it,
// against published figures.
#include <gtest/gtest.h>

#include "color/cie1931.h"
#include "scene/pbrt/params.h"

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
  EXPECT_GT(warm.x, warm.z);
  EXPECT_GT(cold.z, cold.x);
  EXPECT_EQ(pbrt::blackbody_rgb(0.f), RGB(0.f));
  EXPECT_EQ(pbrt::blackbody_rgb(-5.f), RGB(0.f));
}

}  // namespace
}  // namespace lantern
