// Metal: a smooth mirror or a GGX microfacet conductor with complex Fresnel.
#pragma once

#include "material/bsdf_common.h"
#include "material/fresnel.h"
#include "material/microfacet.h"

namespace lantern {

struct ConductorBSDF {
  TrowbridgeReitz distrib;
  Spectrum eta, k;
  Spectrum mirror_reflectance;
  bool mirror;  // constant reflectance instead of Fresnel

  static constexpr bool kReadsComponentNumber = false;  // sample_f draws with u alone

  bool is_specular() const { return distrib.effectively_smooth(); }
  Spectrum fresnel(float cos_i) const { return mirror ? mirror_reflectance : fr_complex(cos_i, eta, k); }

  Spectrum f(const Vec3& wo, const Vec3& wi, TransportMode) const {
    if (!same_hemisphere(wo, wi) || distrib.effectively_smooth()) return Spectrum(0.f);
    float cos_o = abs_cos_theta(wo), cos_i = abs_cos_theta(wi);
    if (cos_i == 0.f || cos_o == 0.f) return Spectrum(0.f);
    Vec3 wm = wi + wo;
    if (glm::dot(wm, wm) == 0.f) return Spectrum(0.f);
    wm = glm::normalize(wm);
    Spectrum F = fresnel(std::fabs(glm::dot(wo, wm)));
    return distrib.D(wm) * F * distrib.G(wo, wi) / (4.f * cos_i * cos_o);
  }

  std::optional<BSDFSample> sample_f(const Vec3& wo, float, Vec2 u, TransportMode, Lobes lobes = Lobes::All) const {
    if (wo.z == 0.f || !has(lobes, Lobes::Reflection)) return std::nullopt;
    BSDFSample s;
    if (distrib.effectively_smooth()) {
      s.wi = Vec3(-wo.x, -wo.y, wo.z);
      s.f = fresnel(abs_cos_theta(s.wi)) / abs_cos_theta(s.wi);
      s.pdf = 1.f;
      s.specular = true;
      return s;
    }
    Vec3 wm = distrib.sample_wm(wo.z < 0.f ? -wo : wo, u);
    if (wo.z < 0.f) wm = -wm;
    Vec3 wi = reflect(wo, wm);
    if (!same_hemisphere(wo, wi)) return std::nullopt;
    float pdf = distrib.pdf(wo, wm) / (4.f * std::fabs(glm::dot(wo, wm)));
    float cos_o = abs_cos_theta(wo), cos_i = abs_cos_theta(wi);
    if (cos_i == 0.f || cos_o == 0.f || !(pdf > 0.f)) return std::nullopt;
    Spectrum F = fresnel(std::fabs(glm::dot(wo, wm)));
    s.f = distrib.D(wm) * F * distrib.G(wo, wi) / (4.f * cos_i * cos_o);
    s.wi = wi;
    s.pdf = pdf;
    return s;
  }

  float pdf(const Vec3& wo, const Vec3& wi, TransportMode, Lobes lobes = Lobes::All) const {
    if (!same_hemisphere(wo, wi) || distrib.effectively_smooth() || !has(lobes, Lobes::Reflection)) return 0.f;
    Vec3 wm = wo + wi;
    if (glm::dot(wm, wm) == 0.f) return 0.f;
    wm = face_forward_z(glm::normalize(wm));
    Vec3 wo_up = wo.z < 0.f ? -wo : wo;
    return distrib.pdf(wo_up, wm) / (4.f * std::fabs(glm::dot(wo, wm)));
  }
};

}  // namespace lantern
