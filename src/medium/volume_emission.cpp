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

RGB GridEmission::at(const Vec3& p) const {
  const float s = scale.density(p);
  if (!(s > 0.f)) return RGB(0.f);
  if (temperature.values.empty()) return Le * s;
  return blackbody.at((temperature.density(p) - offset) * temperature_scale) * s;
}

namespace {

// The largest sample of g that weighs on any point of the unit box region
// [u0, u1] (its trilinear neighbours included).
float max_sample(const DensityGrid& g, const Vec3& u0, const Vec3& u1) {
  int lo[3], hi[3];
  const int n[3] = {g.nx, g.ny, g.nz};
  for (int k = 0; k < 3; ++k) {
    lo[k] = std::max(int(std::floor(u0[k] * float(n[k]) - 0.5f)), 0);
    hi[k] = std::min(int(std::floor(u1[k] * float(n[k]) - 0.5f)) + 1, n[k] - 1);
  }
  float m = 0.f;
  for (int z = lo[2]; z <= hi[2]; ++z)
    for (int y = lo[1]; y <= hi[1]; ++y)
      for (int x = lo[0]; x <= hi[0]; ++x) m = std::max(m, g.values[g.offset(x, y, z)]);
  return m;
}

}  // namespace

float GridEmission::bound(const Vec3& u0, const Vec3& u1) const {
  const float s = max_sample(scale, u0, u1);
  if (!(s > 0.f)) return 0.f;
  if (temperature.values.empty()) return s * max_component(Le);
  // The colour of the hottest sample need not be the brightest, so every
  // sample's colour is looked at.
  int lo[3], hi[3];
  const DensityGrid& g = temperature;
  const int n[3] = {g.nx, g.ny, g.nz};
  for (int k = 0; k < 3; ++k) {
    lo[k] = std::max(int(std::floor(u0[k] * float(n[k]) - 0.5f)), 0);
    hi[k] = std::min(int(std::floor(u1[k] * float(n[k]) - 0.5f)) + 1, n[k] - 1);
  }
  float m = 0.f, hottest = -kInfinity;
  for (int z = lo[2]; z <= hi[2]; ++z)
    for (int y = lo[1]; y <= hi[1]; ++y)
      for (int x = lo[0]; x <= hi[0]; ++x) {
        const float kelvin = (g.values[g.offset(x, y, z)] - offset) * temperature_scale;
        hottest = std::max(hottest, kelvin);
        m = std::max(m, max_component(blackbody.at(kelvin)));
      }
  // Between samples the temperature is interpolated: any colour up to the
  // hottest sample's temperature can appear, so bound by the table's
  // largest value up to it when some sample is hot enough to emit.
  if (hottest > 100.f) m = std::max(m, max_component(blackbody.at(hottest)));
  return s * m;
}

}  // namespace lantern
