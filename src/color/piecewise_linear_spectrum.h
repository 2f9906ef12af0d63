// Spectra given as (wavelength, value) samples: pbrt's inline
// `"spectrum NAME" [lambda0 v0 lambda1 v1 ...]` lists and its spectrum files
// (pbrt-v3's .spd and pbrt-v4's: the same numbers in pairs, with # comments),
// and their linear sRGB in the RGB renderer.
#pragma once

#include <span>
#include <string>
#include <vector>

#include "math/common.h"

namespace lantern {

// pbrt-v4's PiecewiseLinearSpectrum: linear between samples, zero outside
// them. Wavelengths in nm, strictly increasing.
struct PiecewiseLinearSpectrum {
  std::vector<double> nm, value;
  double operator()(double lambda) const;
};

// From interleaved (wavelength, value) pairs. Throws std::invalid_argument
// saying what is wrong: an odd count, no pairs, wavelengths not
// increasing, or a value that is not finite.
PiecewiseLinearSpectrum spectrum_from_pairs(std::span<const double> pairs);

// f(nm) at every nanometre of the visible range sampled (360-830 nm).
template <class F>
PiecewiseLinearSpectrum spectrum_every_nanometre(F&& f) {
  PiecewiseLinearSpectrum s;
  for (int nm = 360; nm <= 830; ++nm) {
    s.nm.push_back(double(nm));
    s.value.push_back(f(nm));
  }
  return s;
}

// Reads a spectrum file. Throws InputError naming the file (and line) for
// an unreadable file, a word that is not a number, or bad pairs.
PiecewiseLinearSpectrum read_spectrum_file(const std::string& path);

// The linear sRGB an emitter with this spectrum shows, normalised to
// luminance 1, as pbrt-v4 divides a light's spectrum by its photometric
// integral (its "scale" then sets the brightness). Black for a spectrum
// without luminance.
RGB illuminant_rgb(const PiecewiseLinearSpectrum& s);

// Planck's law at `kelvin`, tabulated at every nanometre of the range the
// spectral renderer samples (its scale is arbitrary: emitters are
// normalised by luminance).
PiecewiseLinearSpectrum blackbody_spectrum(float kelvin);

// The luminance the film records of spectral radiance s: its integral
// against the CIE 1931 y-bar at 1 nm over 360-830 nm, the sum by which the
// RGB illuminants' white is normalised (color/spectrum_conversion.h).
double spectrum_luminance(const PiecewiseLinearSpectrum& s);

}  // namespace lantern
