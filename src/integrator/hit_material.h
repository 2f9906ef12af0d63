// The material a stored hit is shaded with: a mix resolved to one of its
// materials, and the shading normal perturbed by the material's bump or
// normal map. Shared by every integrator and both kinds of subpath, so a
// light vertex and an eye vertex at the same point shade alike.
#pragma once

#include "integrator/hit.h"
#include "material/bump.h"
#include "material/mix.h"
#include "scene/scene.h"
#include "geometry/shading_geometry.h"
#include "texture/footprint.h"

#include <optional>

namespace lantern {

// dp/du, dp/dv, dn/du, dn/dv and the shading normal of hit i, in the world.
inline ShadingGeometry world_shading_geometry(const Scene& scene, const RayBatch& rays, uint32_t i,
                                              const SurfacePoint& sp) {
  const ShapePools& shapes = scene.shapes;
  const Geometry& geo = shapes.geometries[rays.geom_id[i]];
  // Derivatives in the geometry's own space, carried to the world for an
  // instance (the surface point already is).
  const uint32_t inst = rays.inst_id[i];
  std::optional<Instance> placed;
  if (inst != kInvalidGeometry) placed = instance_at(shapes, inst, rays.time[i]);
  const Instance* in = placed ? &*placed : nullptr;
  SurfacePoint local = in ? local_hit_point(shapes, rays, i, in) : sp;
  ShadingGeometry g;
  switch (geo.kind) {
    case ShapeKind::Mesh: g = triangle_shading_geometry(shapes.meshes[geo.index], rays.prim_id[i], local); break;
    case ShapeKind::Quadric: g = quadric_shading_geometry(shapes.quadrics[geo.index], local); break;
    case ShapeKind::Bilinear:
      g = bilinear_shading_geometry(shapes.patches[geo.index], rays.prim_id[i], Vec2(rays.u[i], rays.v[i]), local);
      break;
    case ShapeKind::Sphere: g = sphere_shading_geometry(shapes.spheres[geo.index], local); break;
    case ShapeKind::Curve:
      g = curve_shading_geometry(shapes.curves[geo.index], rays.prim_id[i], rays.u[i], local);
      break;
  }
  if (in) {
    const glm::mat3 M(in->world_from_object);
    g.dpdu = M * g.dpdu;
    g.dpdv = M * g.dpdv;
    g.surface_dpdu = M * g.surface_dpdu;
    g.surface_dpdv = M * g.surface_dpdv;
    g.dndu = in->normal_to_world * g.dndu;
    g.dndv = in->normal_to_world * g.dndv;
    g.n = sp.ns;
  }
  return g;
}

// The material hit i (reached along d) is shaded with. With footprints on,
// *fp receives the pixel footprint there, which the material's textures,
// its mix and its bump map are evaluated with; off, fp is not touched.
inline MaterialHandle hit_material(const Scene& scene, const FootprintModel& footprints, const RayBatch& rays,
                                   uint32_t i, const Vec3& d, SurfacePoint* sp, Footprint* fp) {
  const Geometry& geo = scene.shapes.geometries[rays.geom_id[i]];
  std::optional<ShadingGeometry> g;
  const Footprint* footprint = nullptr;
  if (footprints.enabled()) {
    g = world_shading_geometry(scene, rays, i, *sp);
    *fp = footprints.at(sp->p, sp->ng, g->uv_dpdu(), g->uv_dpdv());
    footprint = fp;
  }
  MaterialHandle m = resolve_material(geo.material, scene.materials, scene.textures,
                                      TextureContext{sp->p, sp->ng, sp->uv, footprint}, -d);
  const BumpParams* bump = scene.materials.bump(m);
  if (!bump) return m;
  if (!g) g = world_shading_geometry(scene, rays, i, *sp);
  sp->ns = bumped_normal(*bump, scene.textures, *sp, footprint, *g);
  return m;
}

}  // namespace lantern
