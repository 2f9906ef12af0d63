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


double imaging_ratio(const SensorSettings& s) { return double(s.exposure_time) * double(s.iso) / 100.0; }

Matrix3d sensor_rgb_matrix(const SensorSettings& s) {
  Matrix3d m = ColorSpace::srgb().rgb_to_xyz;
  for (auto& row : m)
    for (double& v : row) v *= imaging_ratio(s);
  return m;
}

Matrix3d sensor_matrix(const SensorSettings& s) {
  const double ratio = imaging_ratio(s);
  const ColorSpace& in = ColorSpace::srgb();
  const ColorSpace& out = s.output ? *s.output : in;
  Matrix3d m = rgb_conversion(in, out, false);
  if (s.whitebalance > 0.f) {
    Vec2 source;
    if (s.whitebalance < 4000.f) {
      const Vec3 xyz = blackbody_xyz(s.whitebalance);
      source = Vec2(xyz.x, xyz.y) / (xyz.x + xyz.y + xyz.z);
    } else {
      source = daylight_chromaticity(s.whitebalance);
    }
    m = product(out.xyz_to_rgb, product(white_adaptation(chromaticity_xyz(source), out.white), in.rgb_to_xyz));
  }
  for (auto& row : m)
    for (double& v : row) v *= ratio;
  return m;
}

}  // namespace lantern
