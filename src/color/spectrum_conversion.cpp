#include "color/spectrum_conversion.h"

#include <bit>
#include <cstdint>

#include "color/cie1931.h"
#include "color/color_space.h"
#include "color/rgb_spectrum_table.h"

namespace lantern {

namespace {

// 1 / the integral of D65 times y-bar (1 nm steps, as the tables' whites).
float white_normalisation() { return float(1.0 / illuminant_luminance(cie_d65)); }

// Scenes repeat their colours (a material's constant, a light's), and the
// table's lookup is a search and 24 loads: each thread keeps the last
// answers in a small direct-mapped cache keyed by the colour's bits. A hit
// returns exactly what the table would, so images do not depend on it.
SigmoidPolynomial table_lookup(const RGB& c) {
  struct Entry {
    uint32_t key[3];
    SigmoidPolynomial p;
    bool valid = false;
  };
  thread_local std::array<Entry, 64> cache;
  const uint32_t k[3] = {std::bit_cast<uint32_t>(c[0]), std::bit_cast<uint32_t>(c[1]), std::bit_cast<uint32_t>(c[2])};
  Entry& e = cache[((k[0] * 0x9E3779B1u) ^ (k[1] * 0x85EBCA77u) ^ (k[2] * 0xC2B2AE3Du)) >> 26];
  if (e.valid && e.key[0] == k[0] && e.key[1] == k[1] && e.key[2] == k[2]) return e.p;
  e.key[0] = k[0], e.key[1] = k[1], e.key[2] = k[2];
  e.p = RGBToSpectrumTable::srgb()(c);
  e.valid = true;
  return e.p;
}

// The reflectance-shaped part of an unbounded colour and its scale.
SigmoidPolynomial unbounded_shape(const RGB& c, float* scale) {
  const float m = max_num(max_num(c[0], c[1]), c[2]);
  *scale = 2.f * m;
  if (!(m > 0.f)) return SigmoidPolynomial::constant(0.f);
  return table_lookup(c / *scale);
}

}  // namespace

// The colour space's white at wavelength nm, normalised to luminance 1:
// what illuminant_spectrum multiplies by.
float white_illuminant(float nm) {
  static const float k = white_normalisation();
  return cie_d65(nm) * k;
}

Spectrum albedo_spectrum_sampled(const RGB& c, const SampledWavelengths& l) {
  const SigmoidPolynomial p = table_lookup(clamp(c, 0.f, 1.f));
  Spectrum s;
  for (int i = 0; i < kSpectrumSamples; ++i) s[i] = p(l.nm[size_t(i)]);
  return s;
}

Spectrum unbounded_spectrum_sampled(const RGB& c, const SampledWavelengths& l) { return unbounded_spectrum_of(c).at(l); }

UnboundedSpectrum unbounded_spectrum_of(const RGB& c) {
  UnboundedSpectrum u;
  u.shape = unbounded_shape(max(c, RGB(0.f)), &u.scale);
  return u;
}

Spectrum white_illuminant(const SampledWavelengths& l) {
  Spectrum s;
  for (int i = 0; i < kSpectrumSamples; ++i) s[i] = white_illuminant(l.nm[size_t(i)]);
  return s;
}

Spectrum illuminant_spectrum_sampled(const RGB& c, const SampledWavelengths& l) {
  return unbounded_spectrum_of(c).at(l) * white_illuminant(l);
}

RGB film_rgb_sampled(const Spectrum& s, const SampledWavelengths& l) {
  static const auto m = [] {
    std::array<std::array<float, 3>, 3> f;
    for (size_t i = 0; i < 3; ++i)
      for (size_t j = 0; j < 3; ++j) f[i][j] = float(ColorSpace::srgb().xyz_to_rgb[i][j] / double(kSpectrumSamples));
    return f;
  }();
  Vec3 xyz(0.f);
  for (int i = 0; i < kSpectrumSamples; ++i) {
    const float pdf = l.pdf[size_t(i)];
    if (pdf > 0.f) xyz += cie1931_cmf(l.nm[size_t(i)]) * (s[i] / pdf);  // (a terminated wavelength has none)
  }
  RGB rgb;
  for (size_t i = 0; i < 3; ++i) rgb[int(i)] = m[i][0] * xyz.x + m[i][1] * xyz.y + m[i][2] * xyz.z;
  return rgb;
}

}  // namespace lantern
