// Where colour becomes spectrum, and spectrum colour again. Each conversion
// names what the colour means (Jakob & Hanika 2019, and pbrt-v4's three
// RGB spectrum classes):
//   albedo_spectrum      a reflectance, kept within [0, 1]
//   unbounded_spectrum   a coefficient of any size (eta, k, sigma_a): the
//                        reflectance-shaped spectrum of rgb / (2 max),
//                        times 2 max
//   illuminant_spectrum  an emitter's colour: unbounded, times the colour
//                        space's white illuminant, normalised to
//                        luminance 1 (so RGB (1, 1, 1) is that white at
//                        luminance 1, as in the RGB renderer)
// at the sample's wavelengths (color/sampled_wavelengths.h). In the RGB
// renderer each is the colour itself. film_rgb turns a sample's spectrum
// into the film's linear sRGB: the CIE 1931 observer's XYZ, estimated from
// the sampled wavelengths over their densities, then sRGB's matrix.
//
// Both unbounded forms scale: f(k rgb) = k f(rgb) for k >= 0, so a
// conversion commutes with scaling by a density or a light's "scale".
#pragma once

#include "color/sampled_wavelengths.h"
#include "color/sigmoid_spectrum.h"
#include "math/spectrum.h"

namespace lantern {

Spectrum albedo_spectrum_sampled(const RGB& c, const SampledWavelengths& l);
Spectrum unbounded_spectrum_sampled(const RGB& c, const SampledWavelengths& l);
Spectrum illuminant_spectrum_sampled(const RGB& c, const SampledWavelengths& l);
RGB film_rgb_sampled(const Spectrum& s, const SampledWavelengths& l);

// An unbounded colour's spectrum kept as its shape and scale, to be
// evaluated at many samples' wavelengths without the table's lookup each
// time (an RGB grid medium's samples: medium/grid_density.h).
// unbounded_spectrum_sampled(c, l) == unbounded_spectrum_of(c).at(l), and
// illuminant_spectrum_sampled(c, l) == unbounded_spectrum_of(c).at(l) *
// white_illuminant(l).
struct UnboundedSpectrum {
  SigmoidPolynomial shape = SigmoidPolynomial::constant(0.f);
  float scale = 0.f;
  Spectrum at(const SampledWavelengths& l) const {
    Spectrum s;
    for (int i = 0; i < kSpectrumSamples; ++i) s[i] = scale * shape(l.nm[size_t(i)]);
    return s;
  }
};
UnboundedSpectrum unbounded_spectrum_of(const RGB& c);
// The colour space's white (D65) at wavelength nm, or at the wavelengths,
// normalised to luminance 1.
float white_illuminant(float nm);
Spectrum white_illuminant(const SampledWavelengths& l);

inline Spectrum rgb_channels(const RGB& c) { return Spectrum(c[0], c[1], c[2], c[1]); }

inline Spectrum albedo_spectrum(const RGB& c, const SampledWavelengths& l) {
  return l.is_rgb() ? rgb_channels(c) : albedo_spectrum_sampled(c, l);
}
inline Spectrum unbounded_spectrum(const RGB& c, const SampledWavelengths& l) {
  return l.is_rgb() ? rgb_channels(c) : unbounded_spectrum_sampled(c, l);
}
inline Spectrum illuminant_spectrum(const RGB& c, const SampledWavelengths& l) {
  return l.is_rgb() ? rgb_channels(c) : illuminant_spectrum_sampled(c, l);
}
inline RGB film_rgb(const Spectrum& s, const SampledWavelengths& l) {
  return l.is_rgb() ? RGB(s[0], s[1], s[2]) : film_rgb_sampled(s, l);
}

}  // namespace lantern
