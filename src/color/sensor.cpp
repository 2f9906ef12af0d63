#include "color/sensor.h"

#include <algorithm>

#include "color/cie1931.h"

namespace lantern {

Vec2 daylight_chromaticity(float kelvin) {
  const double T = std::clamp(double(kelvin), 4000.0, 25000.0) * 1.4388 / 1.4380;
  const double x = T <= 7000.0 ? -4.6070e9 / (T * T * T) + 2.9678e6 / (T * T) + 0.09911e3 / T + 0.244063
                               : -2.0064e9 / (T * T * T) + 1.9018e6 / (T * T) + 0.24748e3 / T + 0.237040;
  return Vec2(float(x), float(-3.0 * x * x + 2.870 * x - 0.275));
}

namespace {

Matrix3d product(const Matrix3d& a, const Matrix3d& b) {
  Matrix3d m{};
  for (size_t i = 0; i < 3; ++i)
    for (size_t j = 0; j < 3; ++j)
      for (size_t k = 0; k < 3; ++k) m[i][j] += a[i][k] * b[k][j];
  return m;
}

std::array<double, 3> xyz_of(Vec2 xy) { return {double(xy.x) / double(xy.y), 1.0, (1.0 - xy.x - xy.y) / double(xy.y)}; }

// XYZ to cone responses (Lam's Bradford transform, as used for chromatic
// adaptation in ICC profiles).
constexpr Matrix3d kBradford = {{{0.8951, 0.2664, -0.1614}, {-0.7502, 1.7135, 0.0367}, {0.0389, -0.0685, 1.0296}}};

}  // namespace

Matrix3d sensor_matrix(const SensorSettings& s) {
  const double ratio = double(s.exposure_time) * double(s.iso) / 100.0;
  Matrix3d m{};
  for (size_t i = 0; i < 3; ++i) m[i][i] = ratio;
  if (!(s.whitebalance > 0.f)) return m;
  Vec2 source;
  if (s.whitebalance < 4000.f) {
    const Vec3 xyz = blackbody_xyz(s.whitebalance);
    source = Vec2(xyz.x, xyz.y) / (xyz.x + xyz.y + xyz.z);
  } else {
    source = daylight_chromaticity(s.whitebalance);
  }
  const ColorSpace& cs = ColorSpace::srgb();
  const std::array<double, 3> lms_source = multiply(kBradford, xyz_of(source)), lms_target = multiply(kBradford, cs.white);
  Matrix3d scale{};
  for (size_t i = 0; i < 3; ++i) scale[i][i] = ratio * lms_target[i] / lms_source[i];
  return product(cs.xyz_to_rgb, product(inverse(kBradford), product(scale, product(kBradford, cs.rgb_to_xyz))));
}

}  // namespace lantern
