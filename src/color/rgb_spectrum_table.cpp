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

SigmoidPolynomial RGBToSpectrumTable::operator()(const RGB& in) const {
  const RGB rgb = clamp(in, 0.f, 1.f);
  if (rgb[0] == rgb[1] && rgb[1] == rgb[2]) return SigmoidPolynomial::constant(rgb[0]);
  const int largest = rgb[0] > rgb[1] ? (rgb[0] > rgb[2] ? 0 : 2) : (rgb[1] > rgb[2] ? 1 : 2);
  const float z = rgb[largest];
  const float scale = float(res_ - 1) / z;
  const float x = rgb[(largest + 1) % 3] * scale, y = rgb[(largest + 2) % 3] * scale;
  // The cell: x and y on a uniform grid, z by search among the nodes.
  const int xi = std::min(int(x), res_ - 2), yi = std::min(int(y), res_ - 2);
  const int zi =
      int(std::clamp(std::upper_bound(z_.begin(), z_.end(), z) - z_.begin() - 1, ptrdiff_t(0), ptrdiff_t(res_ - 2)));
  const float dx = x - float(xi), dy = y - float(yi), dz = (z - z_[size_t(zi)]) / (z_[size_t(zi) + 1] - z_[size_t(zi)]);
  float c[3];
  for (int k = 0; k < 3; ++k) {
    auto at = [&](int oz, int oy, int ox) {
      return coefficients_[index(res_, largest, zi + oz, yi + oy, xi + ox) + size_t(k)];
    };
    auto lerp = [](float t, float a, float b) { return (1.f - t) * a + t * b; };
    c[k] = lerp(dz, lerp(dy, lerp(dx, at(0, 0, 0), at(0, 0, 1)), lerp(dx, at(0, 1, 0), at(0, 1, 1))),
                lerp(dy, lerp(dx, at(1, 0, 0), at(1, 0, 1)), lerp(dx, at(1, 1, 0), at(1, 1, 1))));
  }
  return {c[0], c[1], c[2]};
}

}  // namespace lantern
