// A diffuse base under a dielectric coat ("plastic"). The coat reflects with
// Fresnel (smooth or GGX); light that enters is diffusely scattered by the
// base of albedo R, bouncing between base and coat any number of times:
//   f_d = (1 - F(cos_i)) (1 - F(cos_o)) R / (pi eta^2 (1 - R Fdr_int))
// where Fdr_int is the coat's diffuse reflectance seen from inside. This is
// the closed-form layered model of Weidlich & Wilkie 2007 / Kelemen &
// Szirmay-Kalos 2001 as used by Mitsuba's plastic: deterministic, reciprocal
// and energy conserving, so it can take part in exact MIS. It replaces
// pbrt-v4's stochastic random-walk layered BSDF; the looks are close.
#pragma once

#include "material/bsdf_common.h"
#include "material/fresnel.h"
#include "material/microfacet.h"
#include "math/sampling.h"

namespace lantern {

struct CoatedDiffuseBSDF {
  TrowbridgeReitz distrib;
  RGB R;
  float eta;
  float fdr_internal;

  bool is_specular() const { return false; }  // the diffuse lobe is always there
  bool smooth_coat() const { return distrib.effectively_smooth(); }

  // Probability of sampling the coat's reflection rather than the base.
  float coat_probability(float cos_o) const {
    float Fo = fr_dielectric(cos_o, eta);
    float pd = (1.f - Fo) * (R.x + R.y + R.z) / 3.f;
    return Fo + pd > 0.f ? Fo / (Fo + pd) : 1.f;
  }

  RGB f(Vec3 wo, Vec3 wi, TransportMode) const {
    if (!same_hemisphere(wo, wi)) return RGB(0.f);
    if (wo.z < 0.f) {
      wo.z = -wo.z;
      wi.z = -wi.z;
    }
    RGB r = diffuse_term(wo, wi);
    if (!smooth_coat()) r += RGB(coat_term(wo, wi));
    return r;
  }

  float pdf(Vec3 wo, Vec3 wi, TransportMode) const {
    if (!same_hemisphere(wo, wi)) return 0.f;
    if (wo.z < 0.f) {
      wo.z = -wo.z;
      wi.z = -wi.z;
    }
    float pc = coat_probability(wo.z);
    float p = (1.f - pc) * cosine_hemisphere_pdf(wi.z);
    if (!smooth_coat()) {
      Vec3 wm = glm::normalize(wo + wi);
      p += pc * distrib.pdf(wo, wm) / (4.f * std::fabs(glm::dot(wo, wm)));
    }
    return p;
  }

  std::optional<BSDFSample> sample_f(Vec3 wo, float uc, Vec2 u, TransportMode mode) const {
    if (wo.z == 0.f) return std::nullopt;
    bool flip = wo.z < 0.f;
    if (flip) wo.z = -wo.z;
    float pc = coat_probability(wo.z);
    BSDFSample s;
    if (uc < pc) {
      if (smooth_coat()) {
        s.wi = Vec3(-wo.x, -wo.y, wo.z);
        s.f = RGB(fr_dielectric(wo.z, eta) / wo.z);
        s.pdf = pc;
        s.specular = true;
        if (flip) s.wi.z = -s.wi.z;
        return s;
      }
      Vec3 wm = distrib.sample_wm(wo, u);
      s.wi = reflect(wo, wm);
    } else {
      s.wi = sample_cosine_hemisphere(u);
    }
    if (s.wi.z <= 0.f) return std::nullopt;
    s.f = f(wo, s.wi, mode);
    s.pdf = pdf(wo, s.wi, mode);
    if (!(s.pdf > 0.f)) return std::nullopt;
    if (flip) s.wi.z = -s.wi.z;
    return s;
  }

 private:
  RGB diffuse_term(const Vec3& wo, const Vec3& wi) const {
    float Fi = fr_dielectric(wi.z, eta), Fo = fr_dielectric(wo.z, eta);
    RGB inner = R / (RGB(1.f) - R * fdr_internal);
    return inner * ((1.f - Fi) * (1.f - Fo) * kInvPi / (eta * eta));
  }
  float coat_term(const Vec3& wo, const Vec3& wi) const {
    float cos_o = wo.z, cos_i = wi.z;
    if (cos_i == 0.f || cos_o == 0.f) return 0.f;
    Vec3 wm = glm::normalize(wo + wi);
    float F = fr_dielectric(glm::dot(wo, wm), eta);
    return distrib.D(wm) * distrib.G(wo, wi) * F / (4.f * cos_i * cos_o);
  }
};

}  // namespace lantern
