#include "medium/volume_emission.h"

#include <algorithm>

#include "color/cie1931.h"

namespace lantern {

BlackbodyTable::BlackbodyTable(float max_kelvin) {
  // Steps of at most 10 K, and at most 4096 entries: blackbody colours
  // change slowly, and linear interpolation between them is far below the
  // noise of any render.
  const float range = std::max(max_kelvin - kMinKelvin, 1.f);
  const int n = std::clamp(int(range / 10.f) + 2, 2, 4096);
  step_ = range / float(n - 1);
  rgb_.resize(size_t(n));
  for (int i = 0; i < n; ++i) rgb_[size_t(i)] = xyz_to_linear_srgb(blackbody_peak_xyz(kMinKelvin + step_ * float(i)));
}

RGB BlackbodyTable::at(float kelvin) const {
  if (!(kelvin > kMinKelvin) || rgb_.empty()) return RGB(0.f);
  const float x = (kelvin - kMinKelvin) / step_;
  const size_t last = rgb_.size() - 1;
  if (!(x < float(last))) return rgb_[last];
  const size_t i = size_t(x);
  const float t = x - float(i);
  return rgb_[i] * (1.f - t) + rgb_[i + 1] * t;
}

bool TemperatureEmission::tabulate(float largest) {
  const float hottest = std::isinf(largest) ? 1e6f : kelvin(scale >= 0.f ? largest : -largest);
  if (!(hottest > 100.f)) return false;
  blackbody = BlackbodyTable(std::isfinite(hottest) ? std::min(hottest, 1e6f) : 1e6f);
  return true;
}

Spectrum TemperatureEmission::sampled(float value, const SampledWavelengths& l) const {
  const double T = double(kelvin(value));
  if (!(T > 100.0) || blackbody.empty()) return Spectrum(0.f);  // (as BlackbodyTable::at)
  const double peak = blackbody_peak_radiance(T);
  Spectrum s;
  for (int i = 0; i < kSpectrumSamples; ++i) s[i] = float(blackbody_radiance(double(l.nm[size_t(i)]), T) / peak);
  return s;
}

Spectrum GridEmission::at(const Vec3& p, const SampledWavelengths& l) const {
  if (l.is_rgb()) return illuminant_spectrum(at(p), l);
  const float s = scale.density(p);
  if (!(s > 0.f)) return Spectrum(0.f);
  if (temperature.values.empty()) return emitted_spectrum(Le, Le_spectrum ? &*Le_spectrum : nullptr, l) * s;
  return heat.sampled(temperature.density(p), l) * s;
}

RGB GridEmission::at(const Vec3& p) const {
  const float s = scale.density(p);
  if (!(s > 0.f)) return RGB(0.f);
  if (temperature.values.empty()) return Le * s;
  return heat.at(temperature.density(p)) * s;
}

float GridEmission::bound(const Vec3& u0, const Vec3& u1) const {
  const float s = max_over(scale, u0, u1, [&](int x, int y, int z) { return scale.values[scale.offset(x, y, z)]; });
  if (!(s > 0.f)) return 0.f;
  if (temperature.values.empty()) return s * max_component(Le);
  // The brightest colour of the samples' temperatures: not a bound of the
  // colours in between (black bodies do not brighten evenly), but positive
  // wherever an interpolated temperature is hot enough to emit, since some
  // sample then is too. Sampling in proportion to it stays unbiased.
  const DensityGrid& g = temperature;
  return s * max_over(g, u0, u1, [&](int x, int y, int z) { return max_component(heat.at(g.values[g.offset(x, y, z)])); });
}

}  // namespace lantern
