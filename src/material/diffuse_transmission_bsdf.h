// pbrt-v4's diffusetransmission: Lambertian reflection R / pi on the side
// light arrives from and Lambertian transmission T / pi through to the
// other side (leaves, paper, lamp shades). Symmetric, so radiance and
// importance transport alike. The lobe is chosen in proportion to the
// largest channel of R and of T, as in pbrt-v4.
#pragma once

#include "material/bsdf_common.h"
#include "math/sampling.h"

namespace lantern {

struct DiffuseTransmissionBSDF {
  Spectrum R, T;

  bool is_specular() const { return false; }

  Spectrum f(const Vec3& wo, const Vec3& wi, TransportMode) const {
    return (same_hemisphere(wo, wi) ? R : T) * kInvPi;
  }

  std::optional<BSDFSample> sample_f(const Vec3& wo, float uc, Vec2 u, TransportMode,
                                     Lobes lobes = Lobes::All) const {
    float pr, pt;
    if (wo.z == 0.f || !lobe_weights(lobes, &pr, &pt)) return std::nullopt;
    Vec3 wi = sample_cosine_hemisphere(u);
    BSDFSample s;
    if (uc < pr / (pr + pt)) {
      if (wo.z < 0.f) wi.z = -wi.z;
      s.f = R * kInvPi;
      s.pdf = cosine_hemisphere_pdf(std::fabs(wi.z)) * pr / (pr + pt);
    } else {
      if (wo.z > 0.f) wi.z = -wi.z;
      s.f = T * kInvPi;
      s.pdf = cosine_hemisphere_pdf(std::fabs(wi.z)) * pt / (pr + pt);
      s.transmission = true;
    }
    if (!(s.pdf > 0.f)) return std::nullopt;
    s.wi = wi;
    return s;
  }

  float pdf(const Vec3& wo, const Vec3& wi, TransportMode, Lobes lobes = Lobes::All) const {
    float pr, pt;
    if (!lobe_weights(lobes, &pr, &pt)) return 0.f;
    float p = same_hemisphere(wo, wi) ? pr : pt;
    return cosine_hemisphere_pdf(std::fabs(wi.z)) * p / (pr + pt);
  }

 private:
  bool lobe_weights(Lobes lobes, float* pr, float* pt) const {
    *pr = has(lobes, Lobes::Reflection) ? max_component(R) : 0.f;
    *pt = has(lobes, Lobes::Transmission) ? max_component(T) : 0.f;
    return *pr + *pt > 0.f;
  }
};

}  // namespace lantern
