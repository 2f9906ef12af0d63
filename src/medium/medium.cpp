#include "medium/medium.h"

namespace lantern {

Spectrum MediumPools::optical_depth(MediumHandle h, const Vec3& o, const Vec3& d, float s0, float s1, int c, float tau,
                                    const SampledWavelengths& l, float* s_hit) const {
  *s_hit = kInfinity;
  if (h.kind() == MediumKind::RgbGrid) {
    const RgbGrid& g = rgb_grid[h.index()].grid;
    if (!l.is_rgb()) return g.integrate(o, d, s0, s1, c, tau, l, s_hit);
    const int rgb_channel = c < 3 ? c : 1;  // the fourth channel repeats green
    return unbounded_spectrum(g.integrate(o, d, s0, s1, rgb_channel, tau, s_hit), l);
  }
  if (h.kind() == MediumKind::Cloud) {
    const CloudMedium& m = cloud[h.index()];
    return m.sigma_t(l) * m.proxy.integrate(o, d, s0, s1, -1.f, s_hit);
  }
  const MediumKind kind = h.kind();
  const Spectrum sigma_t = kind == MediumKind::Grid  ? grid[h.index()].per_density.sigma_t(l)
                           : kind == MediumKind::Vdb ? vdb[h.index()].per_density.sigma_t(l)
                                                     : homogeneous[h.index()].sigma_t(l);
  const float target = tau >= 0.f && sigma_t[c] > 0.f ? tau / sigma_t[c] : -1.f;
  // The integral of the density: the length itself in a homogeneous medium.
  float D;
  if (kind == MediumKind::Grid) {
    D = grid[h.index()].density.integrate(o, d, s0, s1, target, s_hit);
  } else if (kind == MediumKind::Vdb) {
    D = vdb[h.index()].density.integrate(o, d, s0, s1, target, s_hit);
  } else if (target >= 0.f && target < s1 - s0) {
    *s_hit = s0 + target;
    D = target;
  } else {
    D = s1 - s0;
  }
  // Channels that do not interact stay at zero, even over an infinite stretch.
  Spectrum depth(0.f);
  for (int k = 0; k < Spectrum::kSize; ++k)
    if (sigma_t[k] > 0.f) depth[k] = sigma_t[k] * D;
  return depth;
}

tracking::Track MediumPools::track(MediumHandle h, const Vec3& o, const Vec3& d, float len, float u,
                                   const SampledWavelengths& l, RandomStream& rng) const {
  const CloudMedium& m = cloud[h.index()];
  float ta, tb;
  if (!m.clip(o, d, 0.f, len, &ta, &tb)) return {};
  tracking::Track r = tracking::delta_track(tb - ta, m.sigma_bar(l), u, rng, [&](float t, Spectrum* a, Spectrum* s) {
    m.coefficients(o + d * (ta + t), l, a, s);
  });
  if (r.real()) r.t += ta;
  return r;
}

Spectrum MediumPools::ratio_track(MediumHandle h, const Vec3& o, const Vec3& d, float len, const SampledWavelengths& l,
                                  RandomStream& rng) const {
  const CloudMedium& m = cloud[h.index()];
  float ta, tb;
  if (!m.clip(o, d, 0.f, len, &ta, &tb)) return Spectrum(1.f);
  return tracking::ratio_track(tb - ta, m.sigma_bar(l), rng, [&](float t, Spectrum* a, Spectrum* s) {
    m.coefficients(o + d * (ta + t), l, a, s);
  });
}

}  // namespace lantern
