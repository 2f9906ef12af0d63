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
