#include "color/rgb_spectrum_table.h"

#include <algorithm>
#include <stdexcept>

namespace lantern {

namespace {
float smoothstep(float x) { return x * x * (3.f - 2.f * x); }
}  // namespace

std::vector<float> RGBToSpectrumTable::z_nodes(int res) {
  std::vector<float> z(static_cast<size_t>(res));
  for (int k = 0; k < res; ++k) z[size_t(k)] = smoothstep(smoothstep(float(k) / float(res - 1)));
  return z;
}

RGBToSpectrumTable::RGBToSpectrumTable(int res, std::vector<float> coefficients)
    : RGBToSpectrumTable(res, std::span<const float>(coefficients)) {
  owned_ = std::move(coefficients);  // (moving a vector keeps its storage, which the span views)
}

RGBToSpectrumTable::RGBToSpectrumTable(int res, std::span<const float> coefficients)
    : res_(res), z_(z_nodes(std::max(res, 2))), coefficients_(coefficients) {
  if (res < 2 || coefficients_.size() != index(res, 3, 0, 0, 0))
    throw std::invalid_argument("an RGB-to-spectrum table needs 3 * res^3 * 3 coefficients");
}

bool rgb_table_cell(const RGB& in, int res, std::span<const float> z_nodes, RGBTableCell* cell) {
  const RGB rgb = clamp(in, 0.f, 1.f);
  if (rgb[0] == rgb[1] && rgb[1] == rgb[2]) return false;
  RGBTableCell& c = *cell;
  c.largest = rgb[0] > rgb[1] ? (rgb[0] > rgb[2] ? 0 : 2) : (rgb[1] > rgb[2] ? 1 : 2);
  const float z = rgb[c.largest];
  const float scale = float(res - 1) / z;
  const float x = rgb[(c.largest + 1) % 3] * scale, y = rgb[(c.largest + 2) % 3] * scale;
  // The cell: x and y on a uniform grid, z by search among the nodes.
  c.x = std::min(int(x), res - 2), c.y = std::min(int(y), res - 2);
  c.z = int(std::clamp(std::upper_bound(z_nodes.begin(), z_nodes.end(), z) - z_nodes.begin() - 1, ptrdiff_t(0),
                       ptrdiff_t(res - 2)));
  c.dx = x - float(c.x), c.dy = y - float(c.y);
  c.dz = (z - z_nodes[size_t(c.z)]) / (z_nodes[size_t(c.z) + 1] - z_nodes[size_t(c.z)]);
  return true;
}

SigmoidPolynomial RGBToSpectrumTable::operator()(const RGB& in) const {
  RGBTableCell c;
  if (!rgb_table_cell(in, res_, z_, &c)) return SigmoidPolynomial::constant(clamp(in, 0.f, 1.f)[0]);
  return interpolate_rgb_table(c, [&](int oz, int oy, int ox, int k) {
    return coefficients_[index(res_, c.largest, c.z + oz, c.y + oy, c.x + ox) + size_t(k)];
  });
}

}  // namespace lantern
