// Batch shading: the hits of one material kind are shaded in one loop over
// that kind's bin, with the concrete BSDF type known at compile time. An
// integrator passes a generic lambda; it is instantiated once per kind, so
// there is no virtual call per hit and no kind a scene lacks is ever entered.
#pragma once

#include <cstdint>

#include "material/coated_diffuse_bsdf.h"
#include "material/conductor_bsdf.h"
#include "material/dielectric_bsdf.h"
#include "material/diffuse_bsdf.h"
#include "material/material.h"

namespace lantern {

inline DiffuseBSDF make_bsdf(const DiffuseMaterial& m, Vec2 uv, const TexturePools& tex) {
  return DiffuseBSDF{tex.evaluate(m.reflectance, uv)};
}
inline ConductorBSDF make_bsdf(const ConductorMaterial& m, Vec2, const TexturePools&) {
  return ConductorBSDF{{m.alpha_x, m.alpha_y}, m.eta, m.k, m.mirror_reflectance, m.mirror};
}
inline DielectricBSDF make_bsdf(const DielectricMaterial& m, Vec2, const TexturePools&) {
  return DielectricBSDF{{m.alpha_x, m.alpha_y}, m.eta};
}
inline CoatedDiffuseBSDF make_bsdf(const CoatedDiffuseMaterial& m, Vec2 uv, const TexturePools& tex) {
  return CoatedDiffuseBSDF{DielectricBSDF{{m.alpha_x, m.alpha_y}, m.eta},
                           DiffuseBSDF{tex.evaluate(m.reflectance, uv)},
                           m.thickness,
                           tex.evaluate(m.albedo, uv),
                           m.g,
                           m.max_depth,
                           m.n_samples};
}

// Calls fn(slot, bsdf) for every slot in `bin`; all slots share `kind`.
// material[slot] and uv[slot] describe the hit in that slot.
template <class Fn>
void for_each_bsdf(MaterialKind kind, const MaterialPools& pools, const TexturePools& tex, const uint32_t* bin,
                   size_t count, const MaterialHandle* material, const Vec2* uv, Fn&& fn) {
  auto run = [&](const auto& pool) {
    for (size_t j = 0; j < count; ++j) {
      uint32_t slot = bin[j];
      fn(slot, make_bsdf(pool[material[slot].index()], uv[slot], tex));
    }
  };
  switch (kind) {
    case MaterialKind::Diffuse: run(pools.diffuse); break;
    case MaterialKind::Conductor: run(pools.conductor); break;
    case MaterialKind::Dielectric: run(pools.dielectric); break;
    case MaterialKind::CoatedDiffuse: run(pools.coated_diffuse); break;
  }
}

// Calls fn(bsdf) for one material: a switch, not a virtual call. For the
// scattered lookups of connections, where hits of one kind are not binned.
template <class Fn>
decltype(auto) with_bsdf(MaterialHandle m, const MaterialPools& pools, const TexturePools& tex, Vec2 uv, Fn&& fn) {
  switch (m.kind()) {
    case MaterialKind::Diffuse: return fn(make_bsdf(pools.diffuse[m.index()], uv, tex));
    case MaterialKind::Conductor: return fn(make_bsdf(pools.conductor[m.index()], uv, tex));
    case MaterialKind::Dielectric: return fn(make_bsdf(pools.dielectric[m.index()], uv, tex));
    case MaterialKind::CoatedDiffuse: break;
  }
  return fn(make_bsdf(pools.coated_diffuse[m.index()], uv, tex));
}

// pbrt's correction for shading normals when importance is transported
// (Veach 1997, sec. 5.3): keeps light tracing consistent with camera paths.
// wo points back along the subpath, wi onward; both in world space.
inline float shading_normal_correction(const Vec3& wo, const Vec3& wi, const Vec3& ng, const Vec3& ns) {
  float denom = std::fabs(glm::dot(wo, ng)) * std::fabs(glm::dot(wi, ns));
  return denom > 0.f ? std::fabs(glm::dot(wo, ns)) * std::fabs(glm::dot(wi, ng)) / denom : 0.f;
}

}  // namespace lantern
