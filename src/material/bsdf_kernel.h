// Batch shading: the hits of one material kind are shaded in one loop over
// that kind's bin, with the concrete BSDF type known at compile time. An
// integrator passes a generic lambda; it is instantiated once per kind, so
// there is no virtual call per hit and no kind a scene lacks is ever entered.
#pragma once

#include <cstdint>

#include "color/spectrum_conversion.h"
#include "material/coated_conductor_bsdf.h"
#include "material/coated_diffuse_bsdf.h"
#include "material/conductor_bsdf.h"
#include "material/dielectric_bsdf.h"
#include "material/diffuse_bsdf.h"
#include "material/diffuse_transmission_bsdf.h"
#include "material/hair_bsdf.h"
#include "material/material.h"
#include "material/fourier_bsdf.h"
#include "material/measured_bsdf.h"
#include "material/thin_dielectric_bsdf.h"

namespace lantern {

// Where textures' colours become spectra: a reflectance (clamped to [0, 1])
// or an unbounded coefficient (eta, k, sigma_a).
// A constant given as a spectrum is read at the wavelengths themselves.
inline Spectrum sampled_constant(const TexturePools& tex, const RGBTextureRef& t, const SampledWavelengths& l) {
  const DenselySampledSpectrum& s = tex.spectra[size_t(t.spectrum)];
  Spectrum v;
  for (int i = 0; i < kSpectrumSamples; ++i) v[i] = s(l.nm[size_t(i)]);
  return v;
}
inline bool reads_spectrum(const RGBTextureRef& t, const SampledWavelengths& l) {
  return t.spectrum >= 0 && t.node < 0 && !l.is_rgb();
}
// Whether a reflectance is read by wavelength: a spectrum, or a texture
// tree with one among its leaves (TexturePools::evaluate_albedo).
inline bool reads_albedo_spectrum(const TexturePools& tex, const RGBTextureRef& t, const SampledWavelengths& l) {
  return reads_spectrum(t, l) || (!l.is_rgb() && tex.spectral_tree(t));
}
inline Spectrum reflectance(const TexturePools& tex, const RGBTextureRef& t, const TextureContext& c,
                            const SampledWavelengths& l) {
  if (reads_spectrum(t, l)) return clamp(sampled_constant(tex, t, l), 0.f, 1.f);
  if (!l.is_rgb() && tex.spectral_tree(t)) return clamp(tex.evaluate_albedo(t, c, l), 0.f, 1.f);
  return albedo_spectrum(tex.evaluate_reflectance(t, c), l);
}
// A reflectance times a scale, clamped into [0, 1] after it (pbrt-v4's
// diffusetransmission).
inline Spectrum scaled_reflectance(const TexturePools& tex, const RGBTextureRef& t, float scale, const TextureContext& c,
                                   const SampledWavelengths& l) {
  if (reads_albedo_spectrum(tex, t, l)) return clamp(scale * reflectance(tex, t, c, l), 0.f, 1.f);
  return albedo_spectrum(clamp(scale * tex.evaluate(t, c), 0.f, 1.f), l);
}
inline Spectrum coefficient(const TexturePools& tex, const RGBTextureRef& t, const TextureContext& c,
                            const SampledWavelengths& l) {
  if (reads_spectrum(t, l)) return max(sampled_constant(tex, t, l), Spectrum(0.f));
  return unbounded_spectrum(tex.evaluate(t, c), l);
}
// pbrt-v4's conductor given by its head-on reflectance r: eta 1 and the k
// that gives r.
inline void conductor_from_reflectance(const TexturePools& tex, const RGBTextureRef& t, const TextureContext& c,
                                       const SampledWavelengths& l, Spectrum* eta, Spectrum* k) {
  const Spectrum r = min(reads_albedo_spectrum(tex, t, l) ? reflectance(tex, t, c, l)
                                                         : albedo_spectrum(clamp(tex.evaluate(t, c), 0.f, 0.9999f), l),
                         Spectrum(0.9999f));
  *eta = Spectrum(1.f);
  *k = 2.f * sqrt(r) / sqrt(Spectrum(1.f) - r);
}

inline DiffuseBSDF make_bsdf(const DiffuseMaterial& m, const TextureContext& c, const TexturePools& tex,
                             const SampledWavelengths& l) {
  return DiffuseBSDF{reflectance(tex, m.reflectance, c, l)};
}
inline ConductorBSDF make_bsdf(const ConductorMaterial& m, const TextureContext& c, const TexturePools& tex,
                               const SampledWavelengths& l) {
  if (m.mirror)
    return ConductorBSDF{{0.f, 0.f}, Spectrum(1.f), Spectrum(0.f), reflectance(tex, m.mirror_reflectance, c, l), true};
  TrowbridgeReitz d = m.roughness.distribution(tex, c);
  Spectrum eta, k;
  if (m.by_reflectance)
    conductor_from_reflectance(tex, m.reflectance, c, l, &eta, &k);
  else
    eta = coefficient(tex, m.eta, c, l), k = coefficient(tex, m.k, c, l);
  return ConductorBSDF{d, eta, k, Spectrum(1.f), false};
}
// A dielectric's index: with dispersion, at the sample's first wavelength
// (the integrator keeps that wavelength alone: integrator/dispersion.h).
inline float dielectric_eta(const FloatTextureRef& eta, int32_t dispersion, const TextureContext& c,
                            const TexturePools& tex, const SampledWavelengths& l) {
  const float e = dispersion >= 0 && !l.is_rgb() ? tex.spectra[size_t(dispersion)](l.nm[0]) : tex.evaluate_float(eta, c);
  return e > 0.f ? e : 1.f;
}
// A coat's index: as dielectric_eta, the coat's index a number.
inline float coat_eta(float eta, int32_t dispersion, const TexturePools& tex, const SampledWavelengths& l) {
  return dispersion >= 0 && !l.is_rgb() ? tex.spectra[size_t(dispersion)](l.nm[0]) : eta;
}
inline DielectricBSDF make_bsdf(const DielectricMaterial& m, const TextureContext& c, const TexturePools& tex,
                                const SampledWavelengths& l) {
  return DielectricBSDF{m.roughness.distribution(tex, c), dielectric_eta(m.eta, m.dispersion, c, tex, l)};
}
inline DiffuseTransmissionBSDF make_bsdf(const DiffuseTransmissionMaterial& m, const TextureContext& c,
                                         const TexturePools& tex, const SampledWavelengths& l) {
  return DiffuseTransmissionBSDF{scaled_reflectance(tex, m.reflectance, m.scale, c, l),
                                 scaled_reflectance(tex, m.transmittance, m.scale, c, l)};
}
inline ThinDielectricBSDF make_bsdf(const ThinDielectricMaterial& m, const TextureContext& c, const TexturePools& tex,
                                    const SampledWavelengths& l) {
  return ThinDielectricBSDF{dielectric_eta(m.eta, m.dispersion, c, tex, l)};
}
// The fibre's absorption from a reflectance r, per channel or wavelength:
// Chiang et al. 2016, eq. 9, (ln r / d(beta_n))^2. (r at least 1e-4: a
// black fibre absorbs all but that.)
template <class C>
C hair_sigma_a_from_reflectance(C r, float beta_n) {
  const float b = beta_n;
  const float d =
      5.969f - 0.215f * b + 2.532f * b * b - 10.73f * b * b * b + 5.574f * b * b * b * b + 0.245f * b * b * b * b * b;
  const C l = log(clamp(r, 1e-4f, 1.f)) / d;
  return l * l;
}
// The fibre's absorption from pbrt-v4's three ways of giving it, as pbrt-v4
// evaluates them: sigma_a as an unbounded spectrum; a reflectance as an
// albedo spectrum, inverted at each wavelength (the inversion is not
// linear, though for a smooth spectrum inverting the colour and fitting
// the result differs little: 0.002% on tests/conformance/hair.pbrt's
// orange); melanin concentrations times d'Eon et al. 2011's absorption
// coefficients, an unbounded sRGB colour.
inline Spectrum hair_sigma_a(const HairMaterial& m, const TextureContext& c, const TexturePools& tex, float beta_n,
                             const SampledWavelengths& l) {
  switch (m.by) {
    case HairMaterial::Absorption::SigmaA:
      return unbounded_spectrum(max(tex.evaluate(m.sigma_a, c), RGB(0.f)), l);
    case HairMaterial::Absorption::Reflectance:
      if (!l.is_rgb()) return hair_sigma_a_from_reflectance(reflectance(tex, m.reflectance, c, l), beta_n);
      return rgb_channels(hair_sigma_a_from_reflectance(tex.evaluate(m.reflectance, c), beta_n));
    case HairMaterial::Absorption::Melanin:
      break;
  }
  const float ce = max_num(tex.evaluate_float(m.eumelanin, c), 0.f);
  const float cp = max_num(tex.evaluate_float(m.pheomelanin, c), 0.f);
  return unbounded_spectrum(ce * RGB(0.419f, 0.697f, 1.37f) + cp * RGB(0.187f, 0.4f, 1.05f), l);
}
// h from pbrt's v across the curve; the fibre's direction from the curve's
// tangent, in the shading frame (a curve's shading normal is its normal).
inline HairBSDF make_bsdf(const HairMaterial& m, const TextureContext& c, const TexturePools& tex,
                          const SampledWavelengths& l) {
  const float beta_n = glm::clamp(tex.evaluate_float(m.beta_n, c), 0.f, 1.f);
  const float beta_m = glm::clamp(tex.evaluate_float(m.beta_m, c), 0.f, 1.f);
  const float eta = tex.evaluate_float(m.eta, c);
  const Vec3 tangent = Frame::from_z(c.n).to_local(c.dpdu);
  return HairBSDF(2.f * c.uv.y - 1.f, eta > 0.f ? eta : 1.55f, hair_sigma_a(m, c, tex, beta_n, l), beta_m, beta_n,
                  tex.evaluate_float(m.alpha, c), tangent);
}
inline MeasuredBSDF make_bsdf(const MeasuredMaterial& m, const TextureContext&, const TexturePools&,
                              const SampledWavelengths& l) {
  return MeasuredBSDF{m.brdf, l.nm};
}
inline FourierBSDF make_bsdf(const FourierMaterial& m, const TextureContext&, const TexturePools&,
                             const SampledWavelengths& l) {
  return FourierBSDF{m.table, l};
}
// The layer parameters of a coated material at a point, as pbrt-v4 clamps them.
template <class Top, class Bottom>
LayeredBSDF<Top, Bottom> make_layered(const Top& top, const Bottom& bottom, const CoatLayer& layer,
                                      const TextureContext& c, const TexturePools& tex, const SampledWavelengths& l) {
  return LayeredBSDF<Top, Bottom>{top,
                                  bottom,
                                  max_num(tex.evaluate_float(layer.thickness, c), std::numeric_limits<float>::min()),
                                  reflectance(tex, layer.albedo, c, l),
                                  glm::clamp(tex.evaluate_float(layer.g, c), -0.999f, 0.999f),
                                  layer.max_depth,
                                  layer.n_samples};
}
inline CoatedDiffuseBSDF make_bsdf(const CoatedDiffuseMaterial& m, const TextureContext& c, const TexturePools& tex,
                                   const SampledWavelengths& l) {
  return make_layered(DielectricBSDF{m.roughness.distribution(tex, c), coat_eta(m.eta, m.dispersion, tex, l)},
                      DiffuseBSDF{reflectance(tex, m.reflectance, c, l)}, m.layer, c, tex, l);
}
inline CoatedConductorBSDF make_bsdf(const CoatedConductorMaterial& m, const TextureContext& c, const TexturePools& tex,
                                     const SampledWavelengths& l) {
  Spectrum eta, k;
  if (m.by_reflectance)
    conductor_from_reflectance(tex, m.reflectance, c, l, &eta, &k);
  else
    eta = coefficient(tex, m.conductor_eta, c, l), k = coefficient(tex, m.conductor_k, c, l);
  // The conductor sits in the coat: its index relative to the coat's.
  const float coat = coat_eta(m.interface_eta, m.dispersion, tex, l);
  ConductorBSDF base{m.conductor_roughness.distribution(tex, c), eta / coat, k / coat, Spectrum(1.f), false};
  return make_layered(DielectricBSDF{m.interface_roughness.distribution(tex, c), coat}, base, m.layer, c, tex, l);
}

// The surface attributes textures read, one array per attribute, indexed by
// the slots in a bin.
struct SurfaceAttributes {
  const Vec3* p;
  const Vec3* ng;
  const Vec2* uv;
  const Footprint* fp;               // null: no footprints
  const Vec3* tangent;               // null: no curves
  const SampledWavelengths* lambda;  // the wavelengths of each hit's sample
  TextureContext at(uint32_t slot) const {
    return TextureContext{p[slot], ng[slot], uv[slot], fp ? &fp[slot] : nullptr, tangent ? tangent[slot] : Vec3(0.f)};
  }
};

// Calls fn(slot, bsdf) for every slot in `bin`; all slots share `kind`.
// material[slot] and surface.at(slot) describe the hit in that slot.
template <class Fn>
void for_each_bsdf(MaterialKind kind, const MaterialPools& pools, const TexturePools& tex, const uint32_t* bin,
                   size_t count, const MaterialHandle* material, const SurfaceAttributes& surface, Fn&& fn) {
  auto run = [&](const auto& pool) {
    for (size_t j = 0; j < count; ++j) {
      uint32_t slot = bin[j];
      fn(slot, make_bsdf(pool[material[slot].index()], surface.at(slot), tex, surface.lambda[slot]));
    }
  };
  switch (kind) {
    case MaterialKind::Diffuse:
      run(pools.diffuse);
      break;
    case MaterialKind::Conductor:
      run(pools.conductor);
      break;
    case MaterialKind::Dielectric:
      run(pools.dielectric);
      break;
    case MaterialKind::CoatedDiffuse:
      run(pools.coated_diffuse);
      break;
    case MaterialKind::CoatedConductor:
      run(pools.coated_conductor);
      break;
    case MaterialKind::DiffuseTransmission:
      run(pools.diffuse_transmission);
      break;
    case MaterialKind::ThinDielectric:
      run(pools.thin_dielectric);
      break;
    case MaterialKind::Hair:
      run(pools.hair);
      break;
    case MaterialKind::Measured:
      run(pools.measured);
      break;
    case MaterialKind::Fourier:
      run(pools.fourier);
      break;
    case MaterialKind::Mix:        // resolved when the hit was stored
    case MaterialKind::Interface:  // cut out of the scene
      break;
  }
}

// Calls fn(bsdf) for one material: a switch, not a virtual call. For the
// scattered lookups of connections, where hits of one kind are not binned.
template <class Fn>
decltype(auto) with_bsdf(MaterialHandle m, const MaterialPools& pools, const TexturePools& tex, const TextureContext& c,
                         const SampledWavelengths& l, Fn&& fn) {
  switch (m.kind()) {
    case MaterialKind::Diffuse:
      return fn(make_bsdf(pools.diffuse[m.index()], c, tex, l));
    case MaterialKind::Conductor:
      return fn(make_bsdf(pools.conductor[m.index()], c, tex, l));
    case MaterialKind::Dielectric:
      return fn(make_bsdf(pools.dielectric[m.index()], c, tex, l));
    case MaterialKind::CoatedConductor:
      return fn(make_bsdf(pools.coated_conductor[m.index()], c, tex, l));
    case MaterialKind::DiffuseTransmission:
      return fn(make_bsdf(pools.diffuse_transmission[m.index()], c, tex, l));
    case MaterialKind::ThinDielectric:
      return fn(make_bsdf(pools.thin_dielectric[m.index()], c, tex, l));
    case MaterialKind::Hair:
      return fn(make_bsdf(pools.hair[m.index()], c, tex, l));
    case MaterialKind::Measured:
      return fn(make_bsdf(pools.measured[m.index()], c, tex, l));
    case MaterialKind::Fourier:
      return fn(make_bsdf(pools.fourier[m.index()], c, tex, l));
    case MaterialKind::CoatedDiffuse:
    case MaterialKind::Mix:  // never stored in a hit
    case MaterialKind::Interface:
      break;
  }
  return fn(make_bsdf(pools.coated_diffuse[m.index()], c, tex, l));
}

// pbrt's correction for shading normals when importance is transported
// (Veach 1997, sec. 5.3): keeps light tracing consistent with camera paths.
// wo points back along the subpath, wi onward; both in world space.
inline float shading_normal_correction(const Vec3& wo, const Vec3& wi, const Vec3& ng, const Vec3& ns) {
  float denom = std::fabs(glm::dot(wo, ng)) * std::fabs(glm::dot(wi, ns));
  return denom > 0.f ? std::fabs(glm::dot(wo, ns)) * std::fabs(glm::dot(wi, ng)) / denom : 0.f;
}

}  // namespace lantern
