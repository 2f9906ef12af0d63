// Reconstructing the surface point of a ray hit from the ray batch: the same
// for every integrator and every kind of subpath.
#pragma once

#include "accel/ray_batch.h"
#include "scene/surface.h"

namespace lantern {

inline SurfacePoint hit_point(const ShapePools& shapes, const RayBatch& rays, uint32_t i) {
  const Geometry& g = shapes.geometries[rays.geom_id[i]];
  return g.kind == ShapeKind::Mesh
             ? triangle_point(shapes.meshes[g.index], rays.prim_id[i], rays.u[i], rays.v[i])
             : sphere_point(shapes.spheres[g.index], rays.origin(i) + rays.tfar[i] * rays.direction(i));
}

// Index into LightPools::area of the emitter that was hit, or -1.
inline int64_t hit_area_light(const ShapePools& shapes, const RayBatch& rays, uint32_t i) {
  const Geometry& g = shapes.geometries[rays.geom_id[i]];
  if (g.light_offset < 0) return -1;
  return int64_t(g.light_offset) + (g.kind == ShapeKind::Mesh ? int64_t(rays.prim_id[i]) : 0);
}

}  // namespace lantern
