// Lambertian reflection, two-sided as in pbrt.
#pragma once

#include "material/bsdf_common.h"
#include "math/sampling.h"

namespace lantern {

struct DiffuseBSDF {
  Spectrum R;

  static constexpr bool kAlwaysSpecular = false;
  static constexpr bool kReadsComponentNumber = false;  // sample_f draws with u alone
  bool is_specular() const { return false; }

  Spectrum f(const Vec3& wo, const Vec3& wi, TransportMode) const {
    return same_hemisphere(wo, wi) ? R * kInvPi : Spectrum(0.f);
  }
  std::optional<BSDFSample> sample_f(const Vec3& wo, float, Vec2 u, TransportMode mode,
                                     Lobes lobes = Lobes::All) const {
    if (!has(lobes, Lobes::Reflection)) return std::nullopt;
    Vec3 wi = sample_cosine_hemisphere(u);
    if (wo.z < 0.f) wi.z = -wi.z;
    float pdf = cosine_hemisphere_pdf(std::fabs(wi.z));
    if (pdf == 0.f || wo.z == 0.f) return std::nullopt;
    BSDFSample s;
    s.f = R * kInvPi;
    s.wi = wi;
    s.pdf = pdf;
    return s;
  }
  float pdf(const Vec3& wo, const Vec3& wi, TransportMode, Lobes lobes = Lobes::All) const {
    if (!has(lobes, Lobes::Reflection)) return 0.f;
    return same_hemisphere(wo, wi) ? cosine_hemisphere_pdf(std::fabs(wi.z)) : 0.f;
  }
};

}  // namespace lantern
