// The hits of one bounce: reconstructing the surface point of a ray hit from
// the ray batch, and the per-ray pool the shading stages read, the same for
// every integrator and every kind of subpath.
#pragma once

#include <algorithm>
#include <array>
#include <vector>

#include "accel/ray_batch.h"
#include "color/sampled_wavelengths.h"
#include "entity/shapes.h"
#include "geometry/surface.h"
#include "material/material.h"
#include "texture/mapping.h"

namespace lantern {

// The surface point of hit i in the space of the geometry that was hit:
// the world, or an instanced prototype's own space. Sphere hits take their
// normal from Embree's Ng (hit point minus centre, formed in the ray's
// frame): origin + t * direction would lose a small sphere's shape far from
// the origin.
//
// A triangle hit's barycentrics are clamped onto the triangle: on an edge
// Embree's can fall a rounding outside it (more often in its AVX-512
// kernels), and the point then lay a float's step past the edge, beyond a
// wall's top and above the ceiling that meets it, where its rays to a light
// outside the room went through (tests/extremes_test.cpp, ScaleInvariance).
// With all three barycentrics at least 0, a coordinate that the edge's two
// vertices share is never passed (triangle_point adds only terms of one
// sign to the vertex that has it).
inline Vec2 triangle_barycentrics(float u, float v) {
  u = std::clamp(u, 0.f, 1.f), v = std::clamp(v, 0.f, 1.f);
  if (1.f - u - v < 0.f) v = 1.f - u;  // (as triangle_point forms b0: then exactly 0)
  return Vec2(u, v);
}

inline SurfacePoint local_hit_point(const ShapePools& shapes, const RayBatch& rays, uint32_t i, const Instance* inst) {
  const Geometry& g = shapes.geometries[rays.geom_id[i]];
  if (g.kind == ShapeKind::Mesh) {
    const Vec2 b = triangle_barycentrics(rays.u[i], rays.v[i]);
    return triangle_point(shapes.meshes[g.index], rays.prim_id[i], b.x, b.y);
  }
  if (g.kind == ShapeKind::Quadric) return quadric_point(shapes.quadrics[g.index], Vec2(rays.u[i], rays.v[i]));
  if (g.kind == ShapeKind::Bilinear) return bilinear_point(shapes.patches[g.index], rays.prim_id[i], Vec2(rays.u[i], rays.v[i]));
  if (g.kind == ShapeKind::Curve) {
    // A curve's surface depends on the ray (pbrt's curves face it), so the
    // point is rebuilt from the ray, carried into the prototype's space.
    Vec3 o = rays.origin(i), d = rays.direction(i);
    if (inst) {
      const Mat4 inv = glm::inverse(inst->world_from_object);
      o = Vec3(inv * Vec4(o, 1.f));
      d = glm::mat3(inv) * d;
    }
    return curve_point(shapes.curves[g.index], rays.prim_id[i], rays.u[i], o, d, rays.tfar[i],
                       Vec3(rays.ng_x[i], rays.ng_y[i], rays.ng_z[i]));
  }
  const Sphere& s = shapes.spheres[g.index];
  Vec3 ng(rays.ng_x[i], rays.ng_y[i], rays.ng_z[i]);
  float len = glm::length(ng);
  if (len > 0.f && std::isfinite(len)) return sphere_point_at_normal(s, ng / len);
  Vec3 p = rays.origin(i) + rays.tfar[i] * rays.direction(i);  // the world hit point
  if (inst) p = Vec3(glm::inverse(inst->world_from_object) * Vec4(p, 1.f));
  return sphere_point(s, p);
}

// Carries a prototype-space surface point into the world. The offset scale
// follows the world coordinates or the object's own error times its largest
// stretch, whichever is larger.
inline SurfacePoint to_world(const Instance& inst, const SurfacePoint& local) {
  const Mat4& M = inst.world_from_object;
  SurfacePoint sp = local;
  sp.p = Vec3(M * Vec4(local.p, 1.f));
  sp.ng = glm::normalize(inst.normal_to_world * local.ng);
  sp.ns = glm::normalize(inst.normal_to_world * local.ns);
  if (local.dpdu != Vec3(0.f)) sp.dpdu = glm::normalize(glm::mat3(M) * local.dpdu);
  sp.error_scale = std::copysign(
      max_num(max_abs_component(sp.p), std::fabs(local.error_scale) * inst.stretch + inst.offset), local.error_scale);
  return sp;
}

inline SurfacePoint hit_point(const ShapePools& shapes, const RayBatch& rays, uint32_t i) {
  const uint32_t inst = rays.inst_id[i];
  if (inst == kInvalidGeometry) return local_hit_point(shapes, rays, i, nullptr);
  // Embree reports an instance hit's u, v and Ng in the prototype's space.
  const Instance in = instance_at(shapes, inst, rays.time[i]);
  return to_world(in, local_hit_point(shapes, rays, i, &in));
}

// The cosine that turns a density per solid angle towards a vertex into one
// per area there. A curve that faces the ray (flat, cylinder: marked by a
// negative error_scale) is a fibre that every ray sees across its whole
// width; its area is width times length, and its cosine that of w to the
// fibre's normal plane, whichever ray found the vertex (for that ray it is
// also the cosine to the facing normal).
inline float vertex_cos(const Vec3& ng, float error_scale, const Vec3* tangent, const Vec3& w) {
  if (error_scale < 0.f && tangent && *tangent != Vec3(0.f)) return safe_sqrt(1.f - sqr(glm::dot(w, *tangent)));
  return std::fabs(glm::dot(ng, w));
}
inline const Vec3* tangent_or_null(const std::vector<Vec3>& tangents, uint32_t i) {
  return i < tangents.size() ? &tangents[i] : nullptr;
}

// Index into LightPools::area of the emitter that was hit, or -1.
inline int64_t hit_area_light(const ShapePools& shapes, const RayBatch& rays, uint32_t i) {
  const Geometry& g = shapes.geometries[rays.geom_id[i]];
  if (g.light_offset < 0) return -1;
  const bool per_primitive = g.kind == ShapeKind::Mesh || g.kind == ShapeKind::Bilinear;
  return int64_t(g.light_offset) + (per_primitive ? int64_t(rays.prim_id[i]) : 0);
}

// The hits of one bounce, per ray, binned by material kind for shading.
struct HitPool {
  std::vector<Vec3> p, ng, ns, wo;
  std::vector<Vec2> uv;
  std::vector<float> error_scale;
  std::vector<MaterialHandle> material;
  std::vector<Footprint> footprint;  // empty unless the scene's textures filter
  std::vector<Vec3> tangent;         // empty until a curve is hit
  std::vector<SampledWavelengths> lambda;  // the wavelengths of the hit's sample
  std::vector<uint8_t> alive;  // the path continues past this bounce
  std::vector<Vec3> next_o, next_d;
  std::array<std::vector<uint32_t>, kMaterialKindCount> bins;

  void resize(uint32_t n) {
    for (auto* v : {&p, &ng, &ns, &wo, &next_o, &next_d}) v->resize(n);
    uv.resize(n);
    error_scale.resize(n);
    material.resize(n);
    lambda.resize(n);
    alive.resize(n);
    for (auto& b : bins) b.reserve(n);
  }
  size_t memory_bytes() const {
    size_t b = vector_bytes(p) + vector_bytes(ng) + vector_bytes(ns) + vector_bytes(wo) + vector_bytes(uv) +
               vector_bytes(error_scale) + vector_bytes(material) + vector_bytes(lambda) + vector_bytes(footprint) + vector_bytes(tangent) +
               vector_bytes(alive) + vector_bytes(next_o) + vector_bytes(next_d);
    for (const auto& bin : bins) b += vector_bytes(bin);
    return b;
  }
  void clear_bins() {
    for (auto& b : bins) b.clear();
  }
  // Records hit i (reached travelling along d by a sample of wavelengths l)
  // and puts it in its material's bin; fp: its footprint, when the
  // integrator computes them.
  void store(uint32_t i, const SurfacePoint& sp, const Vec3& d, MaterialHandle m, const SampledWavelengths& l,
             const Footprint* fp) {
    if (fp) {
      if (footprint.size() != p.size()) footprint.resize(p.size());
      footprint[i] = *fp;
    }
    if (sp.dpdu != Vec3(0.f) || !tangent.empty()) {
      if (tangent.size() != p.size()) tangent.resize(p.size());
      tangent[i] = sp.dpdu;
    }
    p[i] = sp.p;
    ng[i] = sp.ng;
    ns[i] = glm::dot(sp.ns, sp.ng) < 0.f ? -sp.ns : sp.ns;  // shading normal on the geometric one's side
    uv[i] = sp.uv;
    wo[i] = -d;
    error_scale[i] = sp.error_scale;
    material[i] = m;
    lambda[i] = l;
    bins[size_t(m.kind())].push_back(i);
  }
  // Copies hit i to j (another path from the same point) and bins it.
  void copy(uint32_t i, uint32_t j) {
    for (auto* v : {&p, &ng, &ns, &wo}) (*v)[j] = (*v)[i];
    uv[j] = uv[i];
    error_scale[j] = error_scale[i];
    material[j] = material[i];
    lambda[j] = lambda[i];
    if (!footprint.empty()) footprint[j] = footprint[i];
    if (!tangent.empty()) tangent[j] = tangent[i];
    alive[j] = 0;
    bins[size_t(material[j].kind())].push_back(j);
  }
  // The next rays of the bounce's surviving paths, in order; active[] is
  // compacted alongside.
  void compact(RayBatch& rays, std::vector<uint32_t>& active) const {
    uint32_t n = 0;
    const uint32_t count = rays.count;
    rays.count = 0;
    for (uint32_t i = 0; i < count; ++i) {
      if (!alive[i]) continue;
      active[n++] = active[i];
      rays.push(next_o[i], next_d[i], 0.f, kInfinity, rays.time[i]);  // (n <= i: time[i] is still this bounce's)
    }
  }
};

}  // namespace lantern
