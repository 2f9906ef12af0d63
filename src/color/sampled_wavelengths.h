// The wavelengths a camera sample carries through the spectral renderer:
// kSpectrumSamples of them, the first drawn from a density that follows
// the eye's sensitivity over 360-830 nm and the others spaced evenly after
// it (wrapping around), so every sample covers the range. A path's
// Spectrum values are its radiance at these wavelengths; the film weighs
// each by the matching functions over its density (color/spectrum_conversion.h).
//
// The RGB renderer carries no wavelengths: SampledWavelengths::rgb(), and
// then a Spectrum's channels are R, G, B and G again (the fourth repeats
// green, so every rule that treats the channels alike, such as choosing one
// to sample a distance in a medium, sees a proper value there).
#pragma once

#include <array>
#include <cmath>

#include "color/sigmoid_spectrum.h"
#include "math/spectrum.h"

namespace lantern {

// The density over visible wavelengths, and its inversion: p(l)
// proportional to 1 / cosh^2(0.0072 (l - 538)) on 360-830 nm
// (Physically Based Rendering, 4th edition, sampling visible wavelengths).
inline float visible_wavelength_pdf(float nm) {
  if (!(nm >= kLambdaMin && nm <= kLambdaMax)) return 0.f;
  const float c = std::cosh(0.0072f * (nm - 538.f));
  return 0.0039398042f / (c * c);
}
// The inversion, with its density: with x = 0.85691062 - 1.82750197 u, 0.0072 (l - 538) is
// -atanh(x) (0.0072 * 138.888889 = 1), and 1 / cosh^2(atanh x) = 1 - x^2,
// so the density needs no hyperbolic function.
inline float sample_visible_wavelength(float u, float* pdf) {
  const float x = 0.85691062f - 1.82750197f * u;
  *pdf = 0.0039398042f * (1.f - x * x);
  return 538.f - 69.4444445f * std::log((1.f + x) / (1.f - x));  // atanh(x) = log((1 + x) / (1 - x)) / 2
}

struct SampledWavelengths {
  std::array<float, kSpectrumSamples> nm{}, pdf{};

  // The RGB renderer's: no wavelengths.
  static SampledWavelengths rgb() { return {}; }
  bool is_rgb() const { return nm[0] == 0.f; }

  // Stratified over u: wavelength i from u + i / kSpectrumSamples.
  static SampledWavelengths sample_visible(float u) {
    SampledWavelengths l;
    for (int i = 0; i < kSpectrumSamples; ++i) {
      float up = u + float(i) / float(kSpectrumSamples);
      if (up >= 1.f) up -= 1.f;
      float pdf;
      const float nm = sample_visible_wavelength(up, &pdf);
      if (nm >= kLambdaMin && nm <= kLambdaMax) {
        l.nm[size_t(i)] = nm, l.pdf[size_t(i)] = pdf;
      } else {  // (rounding at the ends of the range)
        l.nm[size_t(i)] = min_num(max_num(nm, kLambdaMin), kLambdaMax);
        l.pdf[size_t(i)] = visible_wavelength_pdf(l.nm[size_t(i)]);
      }
    }
    return l;
  }

  // Uniform over [lo, hi] (pbrt-v4's Film "spectral" draws them so, which
  // gives every bucket of its range the same share of samples), stratified
  // as above.
  static SampledWavelengths sample_uniform(float u, float lo, float hi) {
    SampledWavelengths l;
    const float width = hi - lo;
    for (int i = 0; i < kSpectrumSamples; ++i) {
      float up = u + float(i) / float(kSpectrumSamples);
      if (up >= 1.f) up -= 1.f;
      l.nm[size_t(i)] = min_num(lo + up * width, hi);
      l.pdf[size_t(i)] = 1.f / width;
    }
    return l;
  }

  // pbrt-v4's form of dispersion: only the first wavelength goes on, the
  // others' densities become zero, and the first's is that of having drawn
  // it among kSpectrumSamples. The integrators reduce the throughput
  // instead and leave the wavelengths alone (integrator/dispersion.h); the
  // film makes the same colour of both (tests/dispersion_test.cpp).
  void terminate_secondary() {
    if (is_rgb() || secondary_terminated()) return;
    for (int i = 1; i < kSpectrumSamples; ++i) pdf[size_t(i)] = 0.f;
    pdf[0] /= float(kSpectrumSamples);
  }
  bool secondary_terminated() const { return pdf[1] == 0.f && !is_rgb(); }
};

}  // namespace lantern
