// The table that turns an RGB reflectance of a colour space into sigmoid
// polynomial coefficients (color/sigmoid_spectrum.h), after Jakob & Hanika
// 2019, sec. 4: the RGB cube split by which channel is largest; within
// each part, nodes over (the other two channels over the largest, the
// largest), the largest spaced densely near 0 and 1; coefficients fitted
// at each node (color/rgb_spectrum_fit.h) and interpolated trilinearly
// between them.
#pragma once

#include <cstddef>
#include <span>
#include <vector>

#include "color/sigmoid_spectrum.h"
#include "math/common.h"

namespace lantern {

// Where a reflectance falls among a table's nodes: the part of the cube
// (its largest channel), the first node of its cell and its position in
// the cell. rgb_table_cell returns false for a grey, whose spectrum is the
// constant (no node needed); z: the table's z nodes.
struct RGBTableCell {
  int largest = 0, x = 0, y = 0, z = 0;
  float dx = 0.f, dy = 0.f, dz = 0.f;
};
bool rgb_table_cell(const RGB& rgb, int res, std::span<const float> z, RGBTableCell* cell);
// The trilinear interpolation of the cell's eight nodes, node(oz, oy, ox, k)
// giving coefficient k of node (z + oz, y + oy, x + ox).
template <class Node>
SigmoidPolynomial interpolate_rgb_table(const RGBTableCell& c, Node&& node) {
  auto lerp = [](float t, float a, float b) { return (1.f - t) * a + t * b; };
  float v[3];
  for (int k = 0; k < 3; ++k)
    v[k] = lerp(c.dz, lerp(c.dy, lerp(c.dx, node(0, 0, 0, k), node(0, 0, 1, k)), lerp(c.dx, node(0, 1, 0, k), node(0, 1, 1, k))),
                lerp(c.dy, lerp(c.dx, node(1, 0, 0, k), node(1, 0, 1, k)), lerp(c.dx, node(1, 1, 0, k), node(1, 1, 1, k))));
  return {v[0], v[1], v[2]};
}

class RGBToSpectrumTable {
 public:
  // res nodes per axis; coefficients: 3 * res^3 * 3 floats, ordered by
  // (largest channel, z, y, x, coefficient); z from z_nodes(res). The
  // table owns them, or (the second form) reads them where they lie.
  RGBToSpectrumTable(int res, std::vector<float> coefficients);
  RGBToSpectrumTable(int res, std::span<const float> coefficients);
  // Moved, not copied: a copy's view would point at the original's storage.
  RGBToSpectrumTable(RGBToSpectrumTable&&) = default;
  RGBToSpectrumTable& operator=(RGBToSpectrumTable&&) = default;
  RGBToSpectrumTable(const RGBToSpectrumTable&) = delete;
  RGBToSpectrumTable& operator=(const RGBToSpectrumTable&) = delete;

  // The spectrum of reflectance rgb (each channel in [0, 1]).
  SigmoidPolynomial operator()(const RGB& rgb) const;

  // sRGB's table, fitted at build time (at 64 nodes per axis, as pbrt-v4's)
  // and embedded in the program.
  static const RGBToSpectrumTable& srgb();

  int resolution() const { return res_; }
  std::span<const float> coefficients() const { return coefficients_; }

  // The values of the largest channel at the nodes: a smoothstep of a
  // smoothstep of k / (res - 1), denser near 0 and 1, where the fit
  // changes fastest.
  static std::vector<float> z_nodes(int res);
  static size_t index(int res, int largest, int z, int y, int x) {
    return 3 * (((size_t(largest) * size_t(res) + size_t(z)) * size_t(res) + size_t(y)) * size_t(res) + size_t(x));
  }

 private:
  int res_;
  std::vector<float> z_;
  std::vector<float> owned_;
  std::span<const float> coefficients_;
};

}  // namespace lantern
