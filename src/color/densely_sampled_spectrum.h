// A spectrum kept as its values at every nanometre over the range the
// spectral renderer samples (360-830 nm), read by linear interpolation:
// what a parameter given as a spectrum (a file, inline pairs, a named
// metal) becomes, so a lookup at a sampled wavelength costs two loads.
#pragma once

#include <array>
#include <cmath>

#include "color/piecewise_linear_spectrum.h"
#include "color/sigmoid_spectrum.h"
#include "color/spectrum_conversion.h"

namespace lantern {

struct DenselySampledSpectrum {
  static constexpr int kCount = int(kLambdaMax - kLambdaMin) + 1;
  std::array<float, kCount> value{};

  explicit DenselySampledSpectrum(const PiecewiseLinearSpectrum& s) {
    for (int i = 0; i < kCount; ++i) value[size_t(i)] = float(s(double(kLambdaMin) + double(i)));
  }
  float operator()(float nm) const {
    const float x = nm - kLambdaMin;
    if (!(x >= 0.f) || x > float(kCount - 1)) return 0.f;
    const int i = std::min(int(x), kCount - 2);
    const float t = x - float(i);
    return (1.f - t) * value[size_t(i)] + t * value[size_t(i) + 1];
  }
};

// An emitter's radiance at the wavelengths l from its colour c: c as an RGB
// illuminant; or, for an emitter given as a spectrum (a black body, a
// file) rendered with sampled wavelengths, that spectrum itself, stored
// divided by its colour's luminance, at the luminance of c (which carries
// the emitter's scale and power).
inline Spectrum emitted_spectrum(const RGB& c, const DenselySampledSpectrum* spectrum, const SampledWavelengths& l) {
  if (!spectrum || l.is_rgb()) return illuminant_spectrum(c, l);
  const float y = luminance(c);
  Spectrum v;
  for (int i = 0; i < kSpectrumSamples; ++i) v[i] = (*spectrum)(l.nm[size_t(i)]) * y;
  return v;
}

}  // namespace lantern
