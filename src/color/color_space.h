// RGB colour spaces as pbrt-v4 names them for `ColorSpace` (srgb, rec2020,
// dci-p3): three primaries and a white illuminant, from which follow the
// matrices between the space's linear RGB and CIE XYZ. The white is the
// illuminant's own XYZ as the tabulated observer (color/cie1931.h) sees
// it, so RGB (1, 1, 1) is exactly that illuminant's colour and the
// spectral renderer's white lands on the RGB renderer's.
#pragma once

#include <array>
#include <string_view>

#include "math/common.h"

namespace lantern {

using Matrix3d = std::array<std::array<double, 3>, 3>;  // row-major

struct ColorSpace {
  std::string_view name;
  float (*illuminant)(float nm);  // the white's relative spectral power
  std::array<double, 3> white;    // its XYZ, Y = 1
  Matrix3d rgb_to_xyz, xyz_to_rgb;

  // The named space, or null: "srgb", "rec2020", "dci-p3".
  static const ColorSpace* named(std::string_view name);
  static const ColorSpace& srgb();
};

// XYZ of the tabulated illuminant, normalised to Y = 1 (integrated at 1 nm).
std::array<double, 3> illuminant_xyz(float (*illuminant)(float nm));

// The space with primaries r, g, b (CIE xy chromaticities) and white
// illuminant `illuminant`.
ColorSpace make_color_space(std::string_view name, Vec2 r, Vec2 g, Vec2 b, float (*illuminant)(float nm));

std::array<double, 3> multiply(const Matrix3d& m, const std::array<double, 3>& v);
// Throws std::invalid_argument for a singular matrix.
Matrix3d inverse(const Matrix3d& m);

}  // namespace lantern
