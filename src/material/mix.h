// pbrt-v4's mix material, resolved before shading: a hit on a mix takes one
// of its two materials, chosen by a hash of the hit point, the direction
// and the mix, so the shading loops only ever see concrete kinds and the
// same hit always gets the same material (bidirectional connections
// included).
#pragma once

#include <bit>

#include "material/material.h"
#include "math/rng.h"

namespace lantern {

inline float mix_hash(const Vec3& p, const Vec3& wo, uint32_t mix) {
  uint64_t h = 0x94D049BB133111EBULL ^ mix;
  for (float v : {p.x, p.y, p.z, wo.x, wo.y, wo.z}) h = mix64(h ^ std::bit_cast<uint32_t>(v));
  return bits_to_unit_float(mix64(h));
}

// The concrete material of a hit at c seen from wo (pointing away).
inline MaterialHandle resolve_material(MaterialHandle m, const MaterialPools& pools, const TexturePools& tex,
                                       const TextureContext& c, const Vec3& wo) {
  while (m.kind() == MaterialKind::Mix) {  // mixes of mixes: as deep as the scene nests them
    const MixMaterial& mix = pools.mix[m.index()];
    float amount = tex.evaluate_float(mix.amount, c);
    if (amount <= 0.f) m = mix.materials[0];
    else if (amount >= 1.f) m = mix.materials[1];
    else m = amount < mix_hash(c.p, wo, m.bits) ? mix.materials[0] : mix.materials[1];
  }
  return m;
}

}  // namespace lantern
