// pbrt-v4's thindielectric: a pane of glass too thin to displace light. Its
// two parallel interfaces reflect R and transmit T = 1 - R at each; summing
// the light bouncing between them gives a total reflectance
// R' = R + T^2 R / (1 - R^2) and T' = 1 - R' (Pharr, Jakob & Humphreys,
// Physically Based Rendering, 4th ed., sec. 9.5.1). Transmission goes
// straight through (wi = -wo), so the relative index along it is 1 and
// radiance is not rescaled.
#pragma once

#include "material/bsdf_common.h"
#include "material/fresnel.h"

namespace lantern {

struct ThinDielectricBSDF {
  float eta;

  bool is_specular() const { return true; }
  Spectrum f(const Vec3&, const Vec3&, TransportMode) const { return Spectrum(0.f); }
  float pdf(const Vec3&, const Vec3&, TransportMode, Lobes = Lobes::All) const { return 0.f; }

  std::optional<BSDFSample> sample_f(const Vec3& wo, float uc, Vec2, TransportMode,
                                     Lobes lobes = Lobes::All) const {
    if (wo.z == 0.f) return std::nullopt;
    float R = fr_dielectric(std::fabs(wo.z), eta), T = 1.f - R;
    if (R < 1.f) {
      R += T * T * R / (1.f - R * R);
      T = 1.f - R;
    }
    float pr = has(lobes, Lobes::Reflection) ? R : 0.f, pt = has(lobes, Lobes::Transmission) ? T : 0.f;
    if (!(pr + pt > 0.f)) return std::nullopt;
    BSDFSample s;
    s.specular = true;
    if (uc < pr / (pr + pt)) {
      s.wi = Vec3(-wo.x, -wo.y, wo.z);
      s.f = Spectrum(R / std::fabs(wo.z));
      s.pdf = pr / (pr + pt);
    } else {
      s.wi = -wo;
      s.f = Spectrum(T / std::fabs(wo.z));
      s.pdf = pt / (pr + pt);
      s.transmission = true;
    }
    return s;
  }
};

}  // namespace lantern
