// pbrt-v4's bump and normal mapping: a material's "displacement" (a float
// texture) or "normalmap" (an image in tangent space, x along dp/du, z along
// the shading normal, read linearly with t flipped and wrapping) perturbs
// dp/du and dp/dv, and the shading normal becomes their cross product,
// turned to the geometric normal's side. The normal map wins when both are
// given, as in pbrt-v4. The displacement's finite differences step half the
// pixel footprint in u and in v (pbrt-v4's 0.0005 where it is zero).
#pragma once

#include "material/material.h"
#include "geometry/shading_geometry.h"

namespace lantern {

inline Vec3 bumped_normal(const BumpParams& b, const TexturePools& tex, const SurfacePoint& sp, const Footprint* fp,
                          const ShadingGeometry& g) {
  Vec3 dpdu, dpdv;
  if (b.normal_map >= 0) {
    const RGB c = tex.cache->lookup_rgb(b.normal_map, TextureLookup{Vec2(sp.uv.x, 1.f - sp.uv.y)});
    Vec3 nl = 2.f * Vec3(c[0], c[1], c[2]) - Vec3(1.f);  // a normal map's colour is a direction
    float len = glm::length(nl);
    if (!(len > 0.f)) return g.n;
    nl /= len;
    Vec3 x = glm::normalize(g.dpdu), z = g.n, y = glm::cross(z, x);
    Vec3 ns = x * nl.x + y * nl.y + z * nl.z;
    float ulen = glm::length(g.dpdu), vlen = glm::length(g.dpdv);
    dpdu = glm::normalize(g.dpdu - glm::dot(g.dpdu, ns) * ns) * ulen;
    dpdv = glm::normalize(glm::cross(ns, dpdu)) * vlen;
  } else {
    const Footprint& f = fp ? *fp : kNoFootprint;
    float du = 0.5f * (std::fabs(f.duvdx.x) + std::fabs(f.duvdy.x));
    float dv = 0.5f * (std::fabs(f.duvdx.y) + std::fabs(f.duvdy.y));
    if (!(du > 0.f)) du = 0.0005f;
    if (!(dv > 0.f)) dv = 0.0005f;
    TextureContext c{sp.p, sp.ng, sp.uv, fp};
    float d0 = tex.evaluate_float(b.displacement, c);
    float d_u = tex.evaluate_float(b.displacement, TextureContext{sp.p + du * g.dpdu, sp.ng, sp.uv + Vec2(du, 0.f), fp});
    float d_v = tex.evaluate_float(b.displacement, TextureContext{sp.p + dv * g.dpdv, sp.ng, sp.uv + Vec2(0.f, dv), fp});
    dpdu = g.dpdu + (d_u - d0) / du * g.n + d0 * g.dndu;
    dpdv = g.dpdv + (d_v - d0) / dv * g.n + d0 * g.dndv;
  }
  Vec3 n = glm::cross(dpdu, dpdv);
  float len = glm::length(n);
  if (!(len > 0.f) || !std::isfinite(len)) return g.n;
  n /= len;
  return glm::dot(n, sp.ng) < 0.f ? -n : n;
}

}  // namespace lantern
