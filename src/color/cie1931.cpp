#include "color/cie1931.h"

#include <cmath>

namespace lantern {

namespace {

// x-bar, y-bar, z-bar from 380 to 780 nm in 5 nm steps (CIE 015:2004,
// Table T.4).
constexpr int kFirstNm = 380, kStepNm = 5, kEntries = 81;
constexpr float kCmf[kEntries][3] = {
    {0.001368f, 0.000039f, 0.006450f}, {0.002236f, 0.000064f, 0.010550f}, {0.004243f, 0.000120f, 0.020050f},
    {0.007650f, 0.000217f, 0.036210f}, {0.014310f, 0.000396f, 0.067850f}, {0.023190f, 0.000640f, 0.110200f},
    {0.043510f, 0.001210f, 0.207400f}, {0.077630f, 0.002180f, 0.371300f}, {0.134380f, 0.004000f, 0.645600f},
    {0.214770f, 0.007300f, 1.039050f}, {0.283900f, 0.011600f, 1.385600f}, {0.328500f, 0.016840f, 1.622960f},
    {0.348280f, 0.023000f, 1.747060f}, {0.348060f, 0.029800f, 1.782600f}, {0.336200f, 0.038000f, 1.772110f},
    {0.318700f, 0.048000f, 1.744100f}, {0.290800f, 0.060000f, 1.669200f}, {0.251100f, 0.073900f, 1.528100f},
    {0.195360f, 0.090980f, 1.287640f}, {0.142100f, 0.112600f, 1.041900f}, {0.095640f, 0.139020f, 0.812950f},
    {0.058950f, 0.169300f, 0.616200f}, {0.032010f, 0.208020f, 0.465180f}, {0.014700f, 0.258600f, 0.353300f},
    {0.004900f, 0.323000f, 0.272000f}, {0.002400f, 0.407300f, 0.212300f}, {0.009300f, 0.503000f, 0.158200f},
    {0.029100f, 0.608200f, 0.111700f}, {0.063270f, 0.710000f, 0.078250f}, {0.109600f, 0.793200f, 0.057250f},
    {0.165500f, 0.862000f, 0.042160f}, {0.225750f, 0.914850f, 0.029840f}, {0.290400f, 0.954000f, 0.020300f},
    {0.359700f, 0.980300f, 0.013400f}, {0.433450f, 0.994950f, 0.008750f}, {0.512050f, 1.000000f, 0.005750f},
    {0.594500f, 0.995000f, 0.003900f}, {0.678400f, 0.978600f, 0.002750f}, {0.762100f, 0.952000f, 0.002100f},
    {0.842500f, 0.915400f, 0.001800f}, {0.916300f, 0.870000f, 0.001650f}, {0.978600f, 0.816300f, 0.001400f},
    {1.026300f, 0.757000f, 0.001100f}, {1.056700f, 0.694900f, 0.001000f}, {1.062200f, 0.631000f, 0.000800f},
    {1.045600f, 0.566800f, 0.000600f}, {1.002600f, 0.503000f, 0.000340f}, {0.938400f, 0.441200f, 0.000240f},
    {0.854450f, 0.381000f, 0.000190f}, {0.751400f, 0.321000f, 0.000100f}, {0.642400f, 0.265000f, 0.000050f},
    {0.541900f, 0.217000f, 0.000030f}, {0.447900f, 0.175000f, 0.000020f}, {0.360800f, 0.138200f, 0.000010f},
    {0.283500f, 0.107000f, 0.000000f}, {0.218700f, 0.081600f, 0.000000f}, {0.164900f, 0.061000f, 0.000000f},
    {0.121200f, 0.044580f, 0.000000f}, {0.087400f, 0.032000f, 0.000000f}, {0.063600f, 0.023200f, 0.000000f},
    {0.046770f, 0.017000f, 0.000000f}, {0.032900f, 0.011920f, 0.000000f}, {0.022700f, 0.008210f, 0.000000f},
    {0.015840f, 0.005723f, 0.000000f}, {0.011359f, 0.004102f, 0.000000f}, {0.008111f, 0.002929f, 0.000000f},
    {0.005790f, 0.002091f, 0.000000f}, {0.004109f, 0.001484f, 0.000000f}, {0.002899f, 0.001047f, 0.000000f},
    {0.002049f, 0.000740f, 0.000000f}, {0.001440f, 0.000520f, 0.000000f}, {0.001000f, 0.000361f, 0.000000f},
    {0.000690f, 0.000249f, 0.000000f}, {0.000476f, 0.000172f, 0.000000f}, {0.000332f, 0.000120f, 0.000000f},
    {0.000235f, 0.000085f, 0.000000f}, {0.000166f, 0.000060f, 0.000000f}, {0.000117f, 0.000042f, 0.000000f},
    {0.000083f, 0.000030f, 0.000000f}, {0.000059f, 0.000021f, 0.000000f}, {0.000042f, 0.000015f, 0.000000f},
};

// D65's relative spectral power from 360 to 830 nm in 5 nm steps (CIE
// 015:2004, Table T.1): the range of pbrt-v4's spectral film, whose
// buckets at the ends see a light's spectrum where the matching functions
// are already zero.
constexpr int kD65FirstNm = 360, kD65Entries = 95;
constexpr float kD65[kD65Entries] = {
    46.6383f, 49.3637f, 52.0891f, 51.0323f, 49.9755f, 52.3118f, 54.6482f, 68.7015f, 82.7549f,
    87.1204f, 91.486f, 92.4589f, 93.4318f, 90.057f, 86.6823f, 95.7736f, 104.865f, 110.936f,
    117.008f, 117.41f, 117.812f, 116.336f, 114.861f, 115.392f, 115.923f, 112.367f, 108.811f,
    109.082f, 109.354f, 108.578f, 107.802f, 106.296f, 104.79f, 106.239f, 107.689f, 106.047f,
    104.405f, 104.225f, 104.046f, 102.023f, 100.0f, 98.1671f, 96.3342f, 96.0611f, 95.788f,
    92.2368f, 88.6856f, 89.3459f, 90.0062f, 89.8026f, 89.5991f, 88.6489f, 87.6987f, 85.4936f,
    83.2886f, 83.4939f, 83.6992f, 81.863f, 80.0268f, 80.1207f, 80.2146f, 81.2462f, 82.2778f,
    80.281f, 78.2842f, 74.0027f, 69.7213f, 70.6652f, 71.6091f, 72.979f, 74.349f, 67.9765f,
    61.604f, 65.7448f, 69.8856f, 72.4863f, 75.087f, 69.3398f, 63.5927f, 55.0054f, 46.4182f,
    56.6118f, 66.8054f, 65.0941f, 63.3828f, 63.8434f, 64.304f, 61.8779f, 59.4519f, 55.7054f,
    51.959f, 54.6998f, 57.4406f, 58.8765f, 60.3125f,
};

}  // namespace

Vec3 cie1931_cmf(float nm) {
  const float x = (nm - float(kFirstNm)) / float(kStepNm);
  if (!(x >= 0.f) || x > float(kEntries - 1)) return Vec3(0.f);
  const int i = std::min(int(x), kEntries - 2);
  const float t = x - float(i);
  return (1.f - t) * Vec3(kCmf[i][0], kCmf[i][1], kCmf[i][2]) +
         t * Vec3(kCmf[i + 1][0], kCmf[i + 1][1], kCmf[i + 1][2]);
}

float cie_d65(float nm) {
  const float x = (nm - float(kD65FirstNm)) / float(kStepNm);
  if (!(x >= 0.f) || x > float(kD65Entries - 1)) return 0.f;
  const int i = std::min(int(x), kD65Entries - 2);
  const float t = x - float(i);
  return (1.f - t) * kD65[i] + t * kD65[i + 1];
}

RGB reflectance_rgb(const std::function<double(double)>& reflectance) {
  // XYZ of the reflected light and of D65 itself, then the sRGB of each; the
  // ratio per channel removes the table's small departure from the exact
  // sRGB white point, so constants map to themselves.
  double reflected[3] = {0.0, 0.0, 0.0}, white[3] = {0.0, 0.0, 0.0};
  for (int nm = kFirstNm; nm <= kFirstNm + kStepNm * (kEntries - 1); ++nm) {
    const Vec3 cmf = cie1931_cmf(float(nm));
    const double light = double(cie_d65(float(nm)));
    const double r = reflectance(double(nm));
    for (int c = 0; c < 3; ++c) {
      white[c] += light * double(cmf[c]);
      reflected[c] += r * light * double(cmf[c]);
    }
  }
  const RGB rgb = xyz_to_linear_srgb(Vec3(float(reflected[0]), float(reflected[1]), float(reflected[2])));
  const RGB rgb_white = xyz_to_linear_srgb(Vec3(float(white[0]), float(white[1]), float(white[2])));
  return rgb / rgb_white;
}

double blackbody_radiance(double nm, double kelvin) {
  const double c = 299792458.0, h = 6.62606957e-34, kb = 1.3806488e-23, l = nm * 1e-9;
  return 2.0 * h * c * c / (std::pow(l, 5) * std::expm1(h * c / (l * kb * kelvin)));
}

double blackbody_peak_radiance(double kelvin) { return blackbody_radiance(2.8977721e6 / kelvin, kelvin); }

namespace {

// XYZ of Planck's law times `scale`, summed at 1 nm over the table.
void planck_xyz(double T, double scale, double xyz[3]) {
  xyz[0] = xyz[1] = xyz[2] = 0.0;
  for (int nm = kFirstNm; nm <= kFirstNm + kStepNm * (kEntries - 1); ++nm) {
    const double radiance = blackbody_radiance(double(nm), T) * scale;
    const Vec3 cmf = cie1931_cmf(float(nm));
    for (int k = 0; k < 3; ++k) xyz[k] += radiance * double(cmf[k]);
  }
}

}  // namespace

Vec3 blackbody_xyz(float kelvin) {
  if (!(kelvin > 0.f)) return Vec3(0.f);
  double xyz[3];
  planck_xyz(double(kelvin), 1.0, xyz);  // the constants' scale cancels in the normalisation
  if (!(xyz[1] > 0.0) || !std::isfinite(xyz[1])) return Vec3(0.f);
  return Vec3(float(xyz[0] / xyz[1]), 1.f, float(xyz[2] / xyz[1]));
}

Vec3 blackbody_peak_xyz(float kelvin) {
  if (!(kelvin > 0.f)) return Vec3(0.f);
  const double T = double(kelvin);
  double xyz[3];
  planck_xyz(T, 1.0 / blackbody_peak_radiance(T), xyz);
  if (!std::isfinite(xyz[1])) return Vec3(0.f);
  return Vec3(float(xyz[0]), float(xyz[1]), float(xyz[2]));
}

}  // namespace lantern
