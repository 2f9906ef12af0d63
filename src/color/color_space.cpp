#include "color/color_space.h"

#include <stdexcept>

#include "color/cie1931.h"
#include "color/cie_daylight.h"

namespace lantern {

std::array<double, 3> illuminant_xyz(float (*illuminant)(float nm)) {
  std::array<double, 3> xyz{0.0, 0.0, 0.0};
  for (int nm = 360; nm <= 830; ++nm) {
    const Vec3 cmf = cie1931_cmf(float(nm));
    const double e = double(illuminant(float(nm)));
    for (int c = 0; c < 3; ++c) xyz[size_t(c)] += e * double(cmf[c]);
  }
  return {xyz[0] / xyz[1], 1.0, xyz[2] / xyz[1]};
}

double illuminant_luminance(float (*illuminant)(float nm)) {
  double y = 0.0;
  for (int nm = 360; nm <= 830; ++nm) y += double(illuminant(float(nm))) * double(cie1931_cmf(float(nm))[1]);
  return y;
}

std::array<double, 3> chromaticity_xyz(Vec2 xy) {
  const double x = double(xy.x), y = double(xy.y);
  return {x / y, 1.0, (1.0 - x - y) / y};
}

std::array<double, 3> multiply(const Matrix3d& m, const std::array<double, 3>& v) {
  std::array<double, 3> r{};
  for (size_t i = 0; i < 3; ++i) r[i] = m[i][0] * v[0] + m[i][1] * v[1] + m[i][2] * v[2];
  return r;
}

Matrix3d product(const Matrix3d& a, const Matrix3d& b) {
  Matrix3d m{};
  for (size_t i = 0; i < 3; ++i)
    for (size_t j = 0; j < 3; ++j)
      for (size_t k = 0; k < 3; ++k) m[i][j] += a[i][k] * b[k][j];
  return m;
}

Matrix3d inverse(const Matrix3d& m) {
  // The adjugate over the determinant.
  const double det = m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) -
                     m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
                     m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
  if (!(std::fabs(det) > 1e-300)) throw std::invalid_argument("singular colour matrix");
  Matrix3d r{};
  for (size_t i = 0; i < 3; ++i)
    for (size_t j = 0; j < 3; ++j) {
      const size_t a = (j + 1) % 3, b = (j + 2) % 3, c = (i + 1) % 3, d = (i + 2) % 3;
      r[i][j] = (m[a][c] * m[b][d] - m[a][d] * m[b][c]) / det;
    }
  return r;
}

// The columns of rgb_to_xyz are the primaries' XYZ (from xy, Y = 1), each
// scaled so that RGB (1, 1, 1) gives the white's XYZ.
namespace {

ColorSpace with_white(std::string_view name, Vec2 r, Vec2 g, Vec2 b, float (*illuminant)(float nm),
                      const std::array<double, 3>& white) {
  ColorSpace cs;
  cs.name = name;
  cs.illuminant = illuminant;
  cs.white = white;
  const Vec2 xy[3] = {r, g, b};
  Matrix3d p{};
  for (size_t k = 0; k < 3; ++k) {
    const std::array<double, 3> primary = chromaticity_xyz(xy[k]);
    for (size_t i = 0; i < 3; ++i) p[i][k] = primary[i];
  }
  const std::array<double, 3> s = multiply(inverse(p), cs.white);
  for (size_t i = 0; i < 3; ++i)
    for (size_t k = 0; k < 3; ++k) cs.rgb_to_xyz[i][k] = p[i][k] * s[k];
  cs.xyz_to_rgb = inverse(cs.rgb_to_xyz);
  return cs;
}

// XYZ to cone responses: Lam's Bradford transform.
constexpr Matrix3d kBradford = {{{0.8951, 0.2664, -0.1614}, {-0.7502, 1.7135, 0.0367}, {0.0389, -0.0685, 1.0296}}};

}  // namespace

ColorSpace make_color_space(std::string_view name, Vec2 r, Vec2 g, Vec2 b, float (*illuminant)(float nm)) {
  return with_white(name, r, g, b, illuminant, illuminant_xyz(illuminant));
}

ColorSpace make_color_space(std::string_view name, Vec2 r, Vec2 g, Vec2 b, Vec2 white) {
  return with_white(name, r, g, b, nullptr, chromaticity_xyz(white));
}

std::array<float, 8> chromaticities(const ColorSpace& cs) {
  std::array<float, 8> c{};
  for (size_t k = 0; k < 4; ++k) {
    const std::array<double, 3> xyz = k < 3 ? std::array<double, 3>{cs.rgb_to_xyz[0][k], cs.rgb_to_xyz[1][k], cs.rgb_to_xyz[2][k]} : cs.white;
    const double sum = xyz[0] + xyz[1] + xyz[2];
    c[2 * k] = float(xyz[0] / sum);
    c[2 * k + 1] = float(xyz[1] / sum);
  }
  return c;
}

Matrix3d white_adaptation(const std::array<double, 3>& from, const std::array<double, 3>& to) {
  const std::array<double, 3> lms_from = multiply(kBradford, from), lms_to = multiply(kBradford, to);
  Matrix3d scale{};
  for (size_t i = 0; i < 3; ++i) scale[i][i] = lms_to[i] / lms_from[i];
  return product(inverse(kBradford), product(scale, kBradford));
}

Matrix3d rgb_conversion(const ColorSpace& from, const ColorSpace& to, bool adapt_white) {
  if (&from == &to) return {{{1.0, 0.0, 0.0}, {0.0, 1.0, 0.0}, {0.0, 0.0, 1.0}}};
  Matrix3d xyz = from.rgb_to_xyz;
  if (adapt_white) xyz = product(white_adaptation(from.white, to.white), xyz);
  return product(to.xyz_to_rgb, xyz);
}

// Primaries: IEC 61966-2-1 (sRGB), ITU-R BT.2020, SMPTE EG 432-1 (DCI-P3
// with a D65 white, as pbrt-v4 defines "dci-p3"), SMPTE ST 2065-1 (ACES's
// AP0 primaries and its white: CIE daylight of chromaticity 0.32168,
// 0.33767, near 6000 K, color/cie_daylight.h, as pbrt-v4 makes its white
// the spectrum "illum-acesD60").
const ColorSpace& ColorSpace::srgb() {
  static const ColorSpace cs = make_color_space("srgb", {0.64f, 0.33f}, {0.30f, 0.60f}, {0.15f, 0.06f}, cie_d65);
  return cs;
}

const ColorSpace* ColorSpace::named(std::string_view name) {
  static const ColorSpace rec2020 =
      make_color_space("rec2020", {0.708f, 0.292f}, {0.170f, 0.797f}, {0.131f, 0.046f}, cie_d65);
  static const ColorSpace p3 =
      make_color_space("dci-p3", {0.680f, 0.320f}, {0.265f, 0.690f}, {0.150f, 0.060f}, cie_d65);
  static const ColorSpace aces =
      make_color_space("aces2065-1", {0.7347f, 0.2653f}, {0.0f, 1.0f}, {0.0001f, -0.0770f}, aces_d60);
  if (name == "srgb") return &srgb();
  if (name == "rec2020") return &rec2020;
  if (name == "dci-p3") return &p3;
  if (name == "aces2065-1") return &aces;
  return nullptr;
}

}  // namespace lantern
