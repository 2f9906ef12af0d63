#include "material/may_be_specular.h"

namespace lantern {

namespace {

// The bound's side of TrowbridgeReitz::effectively_smooth: at the least
// roughness the textures allow (the distribution is smooth below a
// threshold, and its alphas grow with the roughness).
bool may_be_smooth(const RoughnessParams& r, const TexturePools& tex) {
  const auto least_alpha = [&](const FloatTextureRef& t) {
    const float lo = max_num(tex.range(t).lo, 0.f);  // (RoughnessParams::distribution clamps at 0)
    return r.remap ? std::sqrt(lo) : lo;
  };
  return TrowbridgeReitz{least_alpha(r.u), least_alpha(r.v)}.effectively_smooth();
}

// A dielectric interface is specular where it is smooth, and where its index
// is 1, which passes light straight through (DielectricBSDF::is_specular).
bool interface_may_be_specular(const ValueRange& eta, const RoughnessParams& r, const TexturePools& tex) {
  return eta.contains(1.f) || may_be_smooth(r, tex);
}

}  // namespace

bool may_be_specular(const MaterialPools& p, const TexturePools& tex, MaterialHandle m) {
  const uint32_t i = m.index();
  switch (m.kind()) {
    case MaterialKind::Conductor:
      return p.conductor[i].mirror || may_be_smooth(p.conductor[i].roughness, tex);
    case MaterialKind::Dielectric:
      return interface_may_be_specular(tex.range(p.dielectric[i].eta), p.dielectric[i].roughness, tex);
    case MaterialKind::ThinDielectric:
      return true;
    case MaterialKind::CoatedDiffuse: {
      const CoatedDiffuseMaterial& c = p.coated_diffuse[i];
      return interface_may_be_specular({c.eta, c.eta}, c.roughness, tex);
    }
    case MaterialKind::CoatedConductor: {
      const CoatedConductorMaterial& c = p.coated_conductor[i];
      return interface_may_be_specular({c.interface_eta, c.interface_eta}, c.interface_roughness, tex) ||
             may_be_smooth(c.conductor_roughness, tex);
    }
    case MaterialKind::Mix:
      return may_be_specular(p, tex, p.mix[i].materials[0]) || may_be_specular(p, tex, p.mix[i].materials[1]);
    case MaterialKind::Diffuse:
    case MaterialKind::DiffuseTransmission:
    case MaterialKind::Hair:
    case MaterialKind::Measured:
    case MaterialKind::Fourier:
    case MaterialKind::Interface:
      break;  // (no delta lobe; an interface is cut out of the scene)
  }
  return false;
}

std::string kind_that_may_be_specular(const MaterialPools& p, const TexturePools& tex) {
  const auto any = [&](MaterialKind k, size_t count) {
    for (size_t i = 0; i < count; ++i)
      if (may_be_specular(p, tex, MaterialHandle::make(k, uint32_t(i)))) return true;
    return false;
  };
  // (a mix's materials are in these pools too)
  if (any(MaterialKind::Dielectric, p.dielectric.size())) return "dielectric";
  if (any(MaterialKind::ThinDielectric, p.thin_dielectric.size())) return "thindielectric";
  if (any(MaterialKind::Conductor, p.conductor.size())) return "conductor";
  if (any(MaterialKind::CoatedDiffuse, p.coated_diffuse.size())) return "coateddiffuse";
  if (any(MaterialKind::CoatedConductor, p.coated_conductor.size())) return "coatedconductor";
  return {};
}

}  // namespace lantern
