// Fitting sigmoid polynomials to RGB reflectances (Jakob & Hanika 2019,
// sec. 3): the coefficients whose spectrum, lit by the colour space's white
// and seen by the CIE 1931 observer, has the target's colour, found by
// Gauss-Newton iteration on the CIELAB difference (CIE76). What builds the
// tables of color/rgb_spectrum_table.h.
#pragma once

#include <array>
#include <map>
#include <vector>

#include "color/color_space.h"
#include "color/rgb_spectrum_table.h"
#include "color/spectrum_conversion.h"

namespace lantern {

// The largest coefficient a fit may reach (one beyond scales all three
// down to it), and the Gauss-Newton steps it takes at most: Jakob &
// Hanika's optimiser, rgb2spec_opt, fits so.
inline constexpr double kMaxCoefficient = 200.0;
inline constexpr int kFitSteps = 15;

struct SigmoidFit {
  std::array<double, 3> c{0.0, 0.0, 0.0};  // c0, c1, c2 over t in [0, 1]
  double residual = 0.0;                   // CIELAB distance left
};

class SigmoidFitter {
 public:
  explicit SigmoidFitter(const ColorSpace& cs);
  // Fits reflectance rgb (channels in [0, 1]) starting from `start`.
  SigmoidFit fit(const std::array<double, 3>& rgb, const std::array<double, 3>& start) const;
  // The linear RGB of the spectrum with coefficients c under the white.
  std::array<double, 3> rgb_of(const std::array<double, 3>& c) const;

 private:
  static constexpr int kSamples = 471;  // 360-830 nm at 1 nm
  const ColorSpace& cs_;
  std::array<double, kSamples> t_;                   // wavelength mapped onto [0, 1]
  std::array<std::array<double, 3>, kSamples> xyz_;  // quadrature weight * white * cmf / white's Y

  std::array<double, 3> xyz_of(const std::array<double, 3>& c, std::array<double, 9>* jacobian) const;
};

// One column of a table: the coefficients at every z node for (largest
// channel, x node, y node), fitted from a dark node outwards in both
// directions, each node starting from its neighbour's solution (the
// continuation of Jakob & Hanika, sec. 4).
std::vector<std::array<double, 3>> fit_table_column(const SigmoidFitter& fitter, const std::vector<float>& z, int res,
                                                    int largest, int xi, int yi);

// The table of a colour space at 64 nodes per axis, as the build fits
// sRGB's, but fitted only where looked up: a colour's cell's eight nodes,
// the columns through them fitted when first needed (about 1 ms each)
// and kept. Its answers are the whole table's, bit for bit. What the scene
// builder reads colours of other spaces with (rec2020, dci-p3, aces2065-1), whose
// tables the build does not make. Not thread-safe.
class LazyRGBToSpectrumTable {
 public:
  explicit LazyRGBToSpectrumTable(const ColorSpace& cs, int res = 64);
  SigmoidPolynomial operator()(const RGB& rgb);

 private:
  SigmoidFitter fitter_;
  int res_;
  std::vector<float> z_;
  std::map<int, std::vector<std::array<double, 3>>> columns_;  // by (largest * res + y) * res + x
};

// An unbounded colour of the table's space (a medium's coefficient, an
// emitter's colour before its illuminant) as a spectrum: twice its largest
// channel m times the reflectance the table holds for rgb / 2m, as pbrt-v4
// makes one; zero for a colour without a positive channel.
UnboundedSpectrum unbounded_spectrum_in(LazyRGBToSpectrumTable& table, const std::array<double, 3>& rgb);

// The whole table for colour space cs at res nodes per axis (parallel).
RGBToSpectrumTable fit_rgb_to_spectrum_table(const ColorSpace& cs, int res);

}  // namespace lantern
