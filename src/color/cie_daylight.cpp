#include "color/cie_daylight.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace lantern {

namespace {

// CIE 015:2004, Table T.2: S0, S1 and S2 from 300 to 830 nm in 10 nm steps.
constexpr int kDaylightFirstNm = 300, kDaylightStepNm = 10, kDaylightEntries = 54;
constexpr std::array<double, kDaylightEntries> kS0 = {
    0.04,  6.0,   29.6,  55.3,  57.3,  61.8,  61.5,  68.8,  63.4,  65.8,  94.8,  104.8, 105.9, 96.8,
    113.9, 125.6, 125.5, 121.3, 121.3, 113.5, 113.1, 110.8, 106.5, 108.8, 105.3, 104.4, 100.0, 96.0,
    95.1,  89.1,  90.5,  90.3,  88.4,  84.0,  85.1,  81.9,  82.6,  84.9,  81.3,  71.9,  74.3,  76.4,
    63.3,  71.7,  77.0,  65.2,  47.7,  68.6,  65.0,  66.0,  61.0,  53.3,  58.9,  61.9};
constexpr std::array<double, kDaylightEntries> kS1 = {
    0.02,  4.5,   22.4,  42.0,  40.6,  41.6,  38.0,  42.4,  38.5,  35.0,  43.4,  46.3,  43.9,  37.1,
    36.7,  35.9,  32.6,  27.9,  24.3,  20.1,  16.2,  13.2,  8.6,   6.1,   4.2,   1.9,   0.0,   -1.6,
    -3.5,  -3.5,  -5.8,  -7.2,  -8.6,  -9.5,  -10.9, -10.7, -12.0, -14.0, -13.6, -12.0, -13.3, -12.9,
    -10.6, -11.6, -12.2, -10.2, -7.8,  -11.2, -10.4, -10.6, -9.7,  -8.3,  -9.3,  -9.8};
constexpr std::array<double, kDaylightEntries> kS2 = {
    0.0,  2.0,  4.0,  8.5,  7.8,  6.7,  5.3,  6.1,  3.0,  1.2,  -1.1, -0.5, -0.7, -1.2,
    -2.6, -2.9, -2.8, -2.6, -2.6, -1.8, -1.5, -1.3, -1.2, -1.0, -0.5, -0.3, 0.0,  0.2,
    0.5,  2.1,  3.2,  4.1,  4.7,  5.1,  6.7,  7.3,  8.6,  9.8,  10.2, 8.3,  9.6,  8.5,
    7.0,  7.6,  8.0,  6.7,  5.2,  7.4,  6.8,  7.0,  6.4,  5.5,  6.1,  6.5};

DaylightWeights weights_of(double x, double y) {
  const double m = 0.0241 + 0.2562 * x - 0.7341 * y;
  return {(-1.3515 - 1.7703 * x + 5.9114 * y) / m, (0.0300 - 31.4424 * x + 30.0717 * y) / m};
}

}  // namespace

double cie_daylight(double nm, DaylightWeights w) {
  const double t = (nm - double(kDaylightFirstNm)) / double(kDaylightStepNm);
  if (!(t >= 0.0) || t > double(kDaylightEntries - 1)) return 0.0;
  const int i = std::min(int(t), kDaylightEntries - 2);
  const double f = t - double(i);
  auto at = [&](size_t k) { return kS0[k] + w.m1 * kS1[k] + w.m2 * kS2[k]; };
  return (1.0 - f) * at(size_t(i)) + f * at(size_t(i) + 1);
}

DaylightWeights daylight_weights(Vec2 white) { return weights_of(double(white.x), double(white.y)); }

float aces_d60(float nm) {
  static const DaylightWeights w = weights_of(double(kAcesWhite.x), double(kAcesWhite.y));
  return float(cie_daylight(double(nm), w));
}

float cie_d50(float nm) {
  static const DaylightWeights w = [] {
    // The daylight locus (CIE 015:2004, eq. 3.3, 4000-7000 K) at 5000 K on its own scale.
    const double T = 5000.0 * 1.4388 / 1.4380;
    const double x = -4.6070e9 / (T * T * T) + 2.9678e6 / (T * T) + 0.09911e3 / T + 0.244063;
    const double y = -3.0 * x * x + 2.870 * x - 0.275;
    DaylightWeights r = weights_of(x, y);
    r.m1 = std::round(r.m1 * 1000.0) / 1000.0;
    r.m2 = std::round(r.m2 * 1000.0) / 1000.0;
    return r;
  }();
  return float(cie_daylight(double(nm), w));
}

}  // namespace lantern
