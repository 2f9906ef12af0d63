// Glass-like interface: smooth (delta reflection and refraction) or rough
// (Walter et al. 2007 with GGX visible-normal sampling). Radiance crossing the
// interface is scaled by 1/eta^2; importance is not (Veach 1997, ch. 5).
// `lobes` restricts sampling and density to reflection or transmission (the
// probabilities of the other lobe become 0), as layered BSDFs need.
#pragma once

#include "material/bsdf_common.h"
#include "material/fresnel.h"
#include "material/microfacet.h"

namespace lantern {

struct DielectricBSDF {
  TrowbridgeReitz distrib;
  float eta;

  bool is_specular() const { return eta == 1.f || distrib.effectively_smooth(); }

  std::optional<BSDFSample> sample_f(const Vec3& wo, float uc, Vec2 u, TransportMode mode,
                                     Lobes lobes = Lobes::All) const {
    if (wo.z == 0.f) return std::nullopt;
    return is_specular() ? sample_smooth(wo, uc, mode, lobes) : sample_rough(wo, uc, u, mode, lobes);
  }

  Spectrum f(const Vec3& wo, const Vec3& wi, TransportMode mode) const {
    if (is_specular()) return Spectrum(0.f);
    float etap;
    Vec3 wm;
    if (!half_vector(wo, wi, &wm, &etap)) return Spectrum(0.f);
    float cos_o = cos_theta(wo), cos_i = cos_theta(wi);
    float F = fr_dielectric(glm::dot(wo, wm), eta);
    if (cos_i * cos_o > 0.f)
      return Spectrum(distrib.D(wm) * distrib.G(wo, wi) * F / std::fabs(4.f * cos_i * cos_o));
    float denom = sqr(glm::dot(wi, wm) + glm::dot(wo, wm) / etap) * cos_i * cos_o;
    float ft = distrib.D(wm) * (1.f - F) * distrib.G(wo, wi) * std::fabs(glm::dot(wi, wm) * glm::dot(wo, wm) / denom);
    if (mode == TransportMode::Radiance) ft /= sqr(etap);
    return Spectrum(ft);
  }

  float pdf(const Vec3& wo, const Vec3& wi, TransportMode, Lobes lobes = Lobes::All) const {
    if (is_specular()) return 0.f;
    float etap;
    Vec3 wm;
    if (!half_vector(wo, wi, &wm, &etap)) return 0.f;
    float pr, pt;
    if (!lobe_probabilities(fr_dielectric(glm::dot(wo, wm), eta), lobes, &pr, &pt)) return 0.f;
    Vec3 wo_up = wo.z < 0.f ? -wo : wo;
    if (cos_theta(wo) * cos_theta(wi) > 0.f)
      return distrib.pdf(wo_up, wm) / (4.f * std::fabs(glm::dot(wo, wm))) * pr / (pr + pt);
    float denom = sqr(glm::dot(wi, wm) + glm::dot(wo, wm) / etap);
    float dwm_dwi = std::fabs(glm::dot(wi, wm)) / denom;
    return distrib.pdf(wo_up, wm) * dwm_dwi * pt / (pr + pt);
  }

 private:
  // Probabilities of choosing reflection and transmission given the Fresnel
  // reflectance R; false when no allowed lobe has any.
  static bool lobe_probabilities(float R, Lobes lobes, float* pr, float* pt) {
    *pr = has(lobes, Lobes::Reflection) ? R : 0.f;
    *pt = has(lobes, Lobes::Transmission) ? 1.f - R : 0.f;
    return *pr + *pt > 0.f;
  }

  // The generalised half vector of a reflection or refraction pair, facing
  // +z; false for configurations no microfacet can produce.
  bool half_vector(const Vec3& wo, const Vec3& wi, Vec3* wm, float* etap) const {
    float cos_o = cos_theta(wo), cos_i = cos_theta(wi);
    if (cos_i == 0.f || cos_o == 0.f) return false;
    bool reflect = cos_i * cos_o > 0.f;
    *etap = reflect ? 1.f : (cos_o > 0.f ? eta : 1.f / eta);
    Vec3 m = wi * *etap + wo;
    if (glm::dot(m, m) == 0.f) return false;
    m = face_forward_z(glm::normalize(m));
    // Microfacets seen from behind cannot contribute.
    if (glm::dot(m, wi) * cos_i < 0.f || glm::dot(m, wo) * cos_o < 0.f) return false;
    *wm = m;
    return true;
  }

  std::optional<BSDFSample> sample_smooth(const Vec3& wo, float uc, TransportMode mode, Lobes lobes) const {
    float R = fr_dielectric(cos_theta(wo), eta), T = 1.f - R;
    float pr, pt;
    if (!lobe_probabilities(R, lobes, &pr, &pt)) return std::nullopt;
    BSDFSample s;
    s.specular = true;
    if (uc < pr / (pr + pt)) {
      s.wi = Vec3(-wo.x, -wo.y, wo.z);
      s.f = Spectrum(R / abs_cos_theta(s.wi));
      s.pdf = pr / (pr + pt);
      return s;
    }
    float etap;
    Vec3 wi;
    if (!refract(wo, Vec3(0, 0, 1), eta, &etap, &wi)) return std::nullopt;
    float ft = T / abs_cos_theta(wi);
    if (mode == TransportMode::Radiance) ft /= sqr(etap);
    s.wi = wi;
    s.f = Spectrum(ft);
    s.pdf = pt / (pr + pt);
    s.etap = etap;
    s.transmission = true;
    return s;
  }

  std::optional<BSDFSample> sample_rough(const Vec3& wo, float uc, Vec2 u, TransportMode mode, Lobes lobes) const {
    Vec3 wo_up = wo.z < 0.f ? -wo : wo;
    Vec3 wm = distrib.sample_wm(wo_up, u);
    float R = fr_dielectric(glm::dot(wo, wm), eta), T = 1.f - R;
    float pr, pt;
    if (!lobe_probabilities(R, lobes, &pr, &pt)) return std::nullopt;
    BSDFSample s;
    if (uc < pr / (pr + pt)) {
      Vec3 wi = reflect(wo, wm);
      if (!same_hemisphere(wo, wi)) return std::nullopt;
      s.pdf = distrib.pdf(wo_up, wm) / (4.f * std::fabs(glm::dot(wo, wm))) * pr / (pr + pt);
      s.f = Spectrum(distrib.D(wm) * distrib.G(wo, wi) * R / (4.f * cos_theta(wi) * cos_theta(wo)));
      s.wi = wi;
    } else {
      float etap;
      Vec3 wi;
      bool ok = refract(wo, wm, eta, &etap, &wi);
      if (!ok || same_hemisphere(wo, wi) || wi.z == 0.f) return std::nullopt;
      float denom = sqr(glm::dot(wi, wm) + glm::dot(wo, wm) / etap);
      float dwm_dwi = std::fabs(glm::dot(wi, wm)) / denom;
      s.pdf = distrib.pdf(wo_up, wm) * dwm_dwi * pt / (pr + pt);
      float ft = T * distrib.D(wm) * distrib.G(wo, wi) *
                 std::fabs(glm::dot(wi, wm) * glm::dot(wo, wm) / (cos_theta(wi) * cos_theta(wo) * denom));
      if (mode == TransportMode::Radiance) ft /= sqr(etap);
      s.f = Spectrum(ft);
      s.wi = wi;
      s.etap = etap;
      s.transmission = true;
    }
    if (!(s.pdf > 0.f) || !is_finite(s.f)) return std::nullopt;
    return s;
  }
};

}  // namespace lantern
