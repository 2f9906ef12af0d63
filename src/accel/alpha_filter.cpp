#include "accel/alpha_filter.h"

#include <bit>

#include "math/rng.h"
#include "geometry/surface.h"

namespace lantern {

float alpha_at(const ShapePools& shapes, const TexturePools& textures, uint32_t g, uint32_t prim, Vec2 b, Vec3 p) {
  const Geometry& geo = shapes.geometries[g];
  const FloatTextureRef& a = shapes.alpha_masks[size_t(geo.alpha)].alpha;
  if (a.is_constant()) return a.value;
  // A curve's v across its width depends on the ray: textures on curves
  // read u along the curve (pbrt's) and the middle of v.
  if (geo.kind == ShapeKind::Curve)
    return textures.evaluate_float(a, TextureContext{p, Vec3(0, 0, 1), Vec2(shapes.curves[geo.index].curve_u(prim, b.x), 0.5f)});
  if (geo.kind == ShapeKind::Mesh && !shapes.meshes[geo.index].quads.empty())
    prim = quad_hit_triangle(prim, b.x, b.y, &b.x, &b.y);  // Embree's quad: its triangle (geometry/triangle_mesh.h)
  SurfacePoint sp = geo.kind == ShapeKind::Mesh       ? triangle_point(shapes.meshes[geo.index], prim, b.x, b.y)
                    : geo.kind == ShapeKind::Quadric  ? quadric_point(shapes.quadrics[geo.index], b)
                    : geo.kind == ShapeKind::Bilinear ? bilinear_point(shapes.patches[geo.index], prim, b)
                                                      : sphere_point(shapes.spheres[geo.index], p);
  return textures.evaluate_float(a, TextureContext{sp.p, sp.ng, sp.uv});
}

static float hash_unit(std::initializer_list<float> floats, uint32_t prim) {
  uint64_t h = 0xA0761D6478BD642FULL ^ prim;
  for (float v : floats) h = mix64(h ^ std::bit_cast<uint32_t>(v));
  return bits_to_unit_float(mix64(h));
}

void alpha_filter(const RTCFilterFunctionNArguments* args) {
  const auto* d = static_cast<const AlphaFilterData*>(args->geometryUserPtr);
  const unsigned n = args->N;
  for (unsigned i = 0; i < n; ++i) {
    if (args->valid[i] != -1) continue;
    const uint32_t prim = RTCHitN_primID(args->hit, n, i);
    const float t = RTCRayN_tfar(args->ray, n, i);
    const Vec3 o(RTCRayN_org_x(args->ray, n, i), RTCRayN_org_y(args->ray, n, i), RTCRayN_org_z(args->ray, n, i));
    const Vec3 dir(RTCRayN_dir_x(args->ray, n, i), RTCRayN_dir_y(args->ray, n, i), RTCRayN_dir_z(args->ray, n, i));
    const Vec2 b(RTCHitN_u(args->hit, n, i), RTCHitN_v(args->hit, n, i));
    float a = alpha_at(*d->shapes, *d->textures, d->geometry, prim, b, o + t * dir);
    if (a >= 1.f) continue;
    float u = a > 0.f ? hash_unit({o.x, o.y, o.z, dir.x, dir.y, dir.z, t}, prim) : 1.f;
    if (!alpha_keeps(a, u)) args->valid[i] = 0;
  }
}

}  // namespace lantern
