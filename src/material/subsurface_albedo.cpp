#include "material/subsurface_albedo.h"

#include <algorithm>
#include <cmath>

#include <tbb/parallel_for.h>

#include "material/fresnel.h"
#include "math/rng.h"
#include "math/sampling.h"
#include "medium/henyey_greenstein.h"

namespace lantern {

namespace {

// Walks longer than this are counted as absorbed: a vanishing fraction,
// even at an albedo of 0.9999.
constexpr int kMaxScatterings = 20000;

// The direction a walk starts in, inside (z < 0 is depth): one from a
// uniform sky, cosine-weighted as irradiance is, kept with the boundary's
// transmittance, refracted.
Vec3 entering_direction(RandomStream& r, float eta) {
  for (;;) {
    const Vec3 w = sample_cosine_hemisphere(Vec2(r.get1d(), r.get1d()));
    if (r.get1d() < fr_dielectric(w.z, eta)) continue;  // reflected at the surface: not in the slab's light
    const float sin2_t = (1.f - w.z * w.z) / (eta * eta);
    const float cos_t = std::sqrt(std::max(0.f, 1.f - sin2_t));
    const float s = 1.f / eta;
    return Vec3(-w.x * s, -w.y * s, -cos_t);
  }
}

// One walk: true when it leaves through the boundary.
bool walk_leaves(RandomStream& r, float albedo, float eta, const HenyeyGreenstein& phase) {
  Vec3 d = entering_direction(r, eta);
  float z = 0.f;
  for (int n = 0; n < kMaxScatterings; ++n) {
    z += d.z * -std::log(1.f - r.get1d());  // unit extinction: lengths in mean free paths
    if (z >= 0.f) {
      // At the boundary from inside: Fresnel reflection (total beyond the
      // critical angle) or out. The flight restarts at the surface (the
      // exponential forgets how far it went).
      if (r.get1d() >= fr_dielectric(-d.z, eta)) return true;
      d.z = -d.z;
      z = 0.f;
      continue;
    }
    if (r.get1d() >= albedo) return false;
    float pdf;
    d = phase.sample(-d, Vec2(r.get1d(), r.get1d()), &pdf);
  }
  return false;
}

}  // namespace

float slab_albedo(float albedo, float eta, float g, int walks) {
  const HenyeyGreenstein phase{g};
  int left = 0;
  for (int i = 0; i < walks; ++i) {
    RandomStream r = RandomStream::make(0x5AB, uint64_t(i), uint64_t(std::llround(double(albedo) * 1e6)));
    left += walk_leaves(r, albedo, eta, phase);
  }
  return float(left) / float(walks);
}

// 33 albedos, denser towards 1 where the slab's answer changes fastest,
// each of 4096 walks (a standard error under 0.008).
SlabAlbedoTable::SlabAlbedoTable(float eta, float g) {
  constexpr int kPoints = 32;
  albedo_.resize(kPoints + 1);
  slab_.resize(kPoints + 1);
  for (int i = 0; i <= kPoints; ++i) {
    const float t = float(i) / float(kPoints);
    albedo_[size_t(i)] = i == kPoints ? 0.9999f : 1.f - (1.f - t) * (1.f - t) * (1.f - t);
  }
  // Each entry on its own numbers: the same table on any number of threads.
  tbb::parallel_for(0, kPoints + 1, [&](int i) { slab_[size_t(i)] = slab_albedo(albedo_[size_t(i)], eta, g, 4096); });
  // Monotone by construction: noise must not fold the inverse.
  for (size_t i = 1; i < slab_.size(); ++i) slab_[i] = std::max(slab_[i], slab_[i - 1]);
}

float SlabAlbedoTable::single_scattering_albedo(float reflectance) const {
  const float R = std::clamp(reflectance, 0.f, 1.f);
  if (R >= slab_.back()) return albedo_.back();
  const size_t i = size_t(std::upper_bound(slab_.begin(), slab_.end(), R) - slab_.begin());
  if (i == 0) return 0.f;
  const float span = slab_[i] - slab_[i - 1];
  const float t = span > 0.f ? (R - slab_[i - 1]) / span : 0.f;
  return albedo_[i - 1] + t * (albedo_[i] - albedo_[i - 1]);
}

}  // namespace lantern
