// RGB colour spaces as pbrt-v4 names them for `ColorSpace` (srgb, rec2020,
// dci-p3, aces2065-1): three primaries and a white, from which follow the
// matrices between the space's linear RGB and CIE XYZ. Where the white is
// a tabulated illuminant, it is that illuminant's own XYZ as the tabulated
// observer (color/cie1931.h) sees it, so RGB (1, 1, 1) is exactly that
// illuminant's colour and the spectral renderer's white lands on the RGB
// renderer's.
#pragma once

#include <array>
#include <string_view>

#include "math/common.h"

namespace lantern {

using Matrix3d = std::array<std::array<double, 3>, 3>;  // row-major

struct ColorSpace {
  std::string_view name;
  // The white's relative spectral power (D65, or ACES's daylight); null
  // for a space made with its white's chromaticity alone.
  float (*illuminant)(float nm);
  std::array<double, 3> white;  // its XYZ, Y = 1
  Matrix3d rgb_to_xyz, xyz_to_rgb;

  // The named space, or null: "srgb", "rec2020", "dci-p3", "aces2065-1".
  static const ColorSpace* named(std::string_view name);
  static const ColorSpace& srgb();
};

// The primaries' and the white's CIE xy: rx ry gx gy bx by wx wy (the
// order of OpenEXR's chromaticities attribute).
std::array<float, 8> chromaticities(const ColorSpace& cs);

// The XYZ, with Y = 1, of CIE xy chromaticity xy.
std::array<double, 3> chromaticity_xyz(Vec2 xy);

// XYZ of the tabulated illuminant, normalised to Y = 1 (integrated at 1 nm).
std::array<double, 3> illuminant_xyz(float (*illuminant)(float nm));
// Its luminance: the integral of it times y-bar over 360-830 nm, at 1 nm
// (what an emitter's spectrum is divided by to have luminance 1).
double illuminant_luminance(float (*illuminant)(float nm));

// The space with primaries r, g, b (CIE xy chromaticities) and white
// illuminant `illuminant`.
ColorSpace make_color_space(std::string_view name, Vec2 r, Vec2 g, Vec2 b, float (*illuminant)(float nm));
// The same with a white given by its CIE xy chromaticity.
ColorSpace make_color_space(std::string_view name, Vec2 r, Vec2 g, Vec2 b, Vec2 white);

// A von Kries adaptation in Bradford's cone space (Lam's transform, as ICC
// profiles use it): the XYZ matrix that takes white `from` to white `to`
// (both XYZ) and scales every cone response by the same ratios.
Matrix3d white_adaptation(const std::array<double, 3>& from, const std::array<double, 3>& to);

// Linear RGB of `from` to linear RGB of `to`: through XYZ, and, with
// adapt_white, through the adaptation of from's white to to's, so RGB
// (1, 1, 1) stays (1, 1, 1) (what a reflectance's colour, defined under
// its space's white, needs); without, the colour of the same light.
Matrix3d rgb_conversion(const ColorSpace& from, const ColorSpace& to, bool adapt_white);

std::array<double, 3> multiply(const Matrix3d& m, const std::array<double, 3>& v);
Matrix3d product(const Matrix3d& a, const Matrix3d& b);
// Throws std::invalid_argument for a singular matrix.
Matrix3d inverse(const Matrix3d& m);

}  // namespace lantern
