// Alpha cutouts inside Embree: an intersection and an occlusion filter
// function, registered only on geometries that have an alpha texture, so
// every ray kind and every back end honours them and a scene without alpha
// runs no filter at all. As in pbrt-v4, a hit where alpha is 0 is ignored, and
// one where 0 < alpha < 1 is kept with probability alpha by comparing alpha
// with a hash of the ray and the hit: deterministic, so images stay
// bit-identical across thread counts, and independent from one crossing of
// a ray to the next (pbrt-v4 gets that by spawning a new ray at each
// rejected hit; here the hit distance and primitive enter the hash).
#pragma once

#include <embree3/rtcore.h>

#include "entity/shapes.h"

namespace lantern {

struct AlphaFilterData {
  const ShapePools* shapes;
  const TexturePools* textures;
  uint32_t geometry;  // index into shapes->geometries
};

// The alpha of geometry g at primitive prim, barycentrics (b1, b2) for a
// triangle, surface coordinates b for a quadric, or point p on a sphere (in
// the space the geometry is stored in).
float alpha_at(const ShapePools& shapes, const TexturePools& textures, uint32_t g, uint32_t prim, Vec2 b, Vec3 p);

// Whether a hit with this alpha is kept, for the hash value u in [0, 1).
inline bool alpha_keeps(float alpha, float u) { return alpha >= 1.f || (alpha > 0.f && u < alpha); }

void alpha_filter(const RTCFilterFunctionNArguments* args);

}  // namespace lantern
