#include "color/spectrum_conversion.h"

#include "color/cie1931.h"
#include "color/color_space.h"
#include "color/rgb_spectrum_table.h"

namespace lantern {

namespace {

// 1 / the integral of D65 times y-bar (1 nm steps, as the tables' whites).
float white_normalisation() {
  double y = 0.0;
  for (int nm = 360; nm <= 830; ++nm) y += double(cie_d65(float(nm))) * double(cie1931_cmf(float(nm))[1]);
  return float(1.0 / y);
}

// The reflectance-shaped part of an unbounded colour and its scale.
SigmoidPolynomial unbounded_shape(const RGB& c, float* scale) {
  const float m = std::fmax(std::fmax(c[0], c[1]), c[2]);
  *scale = 2.f * m;
  if (!(m > 0.f)) return SigmoidPolynomial::constant(0.f);
  return RGBToSpectrumTable::srgb()(c / *scale);
}

}  // namespace

float white_illuminant(float nm) {
  static const float k = white_normalisation();
  return cie_d65(nm) * k;
}

Spectrum albedo_spectrum_sampled(const RGB& c, const SampledWavelengths& l) {
  const SigmoidPolynomial p = RGBToSpectrumTable::srgb()(clamp(c, 0.f, 1.f));
  Spectrum s;
  for (int i = 0; i < kSpectrumSamples; ++i) s[i] = p(l.nm[size_t(i)]);
  return s;
}

Spectrum unbounded_spectrum_sampled(const RGB& c, const SampledWavelengths& l) {
  float scale;
  const SigmoidPolynomial p = unbounded_shape(max(c, RGB(0.f)), &scale);
  Spectrum s;
  for (int i = 0; i < kSpectrumSamples; ++i) s[i] = scale * p(l.nm[size_t(i)]);
  return s;
}

Spectrum illuminant_spectrum_sampled(const RGB& c, const SampledWavelengths& l) {
  float scale;
  const SigmoidPolynomial p = unbounded_shape(max(c, RGB(0.f)), &scale);
  Spectrum s;
  for (int i = 0; i < kSpectrumSamples; ++i) s[i] = scale * p(l.nm[size_t(i)]) * white_illuminant(l.nm[size_t(i)]);
  return s;
}

RGB film_rgb_sampled(const Spectrum& s, const SampledWavelengths& l) {
  double xyz[3] = {0.0, 0.0, 0.0};
  for (int i = 0; i < kSpectrumSamples; ++i) {
    const float pdf = l.pdf[size_t(i)];
    if (!(pdf > 0.f)) continue;  // a terminated wavelength
    const Vec3 cmf = cie1931_cmf(l.nm[size_t(i)]);
    for (int k = 0; k < 3; ++k) xyz[k] += double(s[i]) * double(cmf[k]) / double(pdf);
  }
  for (double& v : xyz) v /= double(kSpectrumSamples);
  const std::array<double, 3> rgb = multiply(ColorSpace::srgb().xyz_to_rgb, {xyz[0], xyz[1], xyz[2]});
  return RGB(float(rgb[0]), float(rgb[1]), float(rgb[2]));
}

}  // namespace lantern
