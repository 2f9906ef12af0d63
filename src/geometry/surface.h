// A point on a shape with its oriented normals, reconstructed the same way
// for ray hits and for light samples (pbrt's orientation rules: a mesh with
// per-vertex N faces its geometric normal towards N; otherwise the winding
// normal, flipped by ReverseOrientation or a handedness-swapping transform).
#pragma once

#include "geometry/quadric.h"
#include "geometry/triangle_mesh.h"

namespace lantern {

struct SurfacePoint {
  Vec3 p;
  Vec3 ng;  // oriented geometric normal (unit)
  Vec3 ns;  // shading normal (unit), on the same side as ng
  Vec2 uv;
  float error_scale;  // magnitude the position's rounding error scales with
  Vec3 dpdu{0.f};     // curves only: the unit tangent (pbrt's hair BSDF is defined around it)
};

inline SurfacePoint triangle_point(const TriangleMesh& m, uint32_t prim, float b1, float b2) {
  const glm::uvec3 t = m.triangle(prim);
  const Vec3 &p0 = m.positions[t.x], &p1 = m.positions[t.y], &p2 = m.positions[t.z];
  float b0 = 1.f - b1 - b2;
  SurfacePoint sp;
  // From the vertex of the largest barycentric along the edges: where the
  // vertices share a coordinate (a triangle in a plane z = c) the point has
  // it exactly, whatever the barycentrics' rounding (b0 + b1 + b2 need not
  // be 1 in floats), so a 3D texture whose boundary is that plane does not
  // flip side from hit to hit (tests/texture_test.cpp); and a vertex, or a
  // point of an edge, depends on that vertex or edge alone.
  if (b0 >= b1 && b0 >= b2)
    sp.p = p0 + b1 * (p1 - p0) + b2 * (p2 - p0);
  else if (b1 >= b2)
    sp.p = p1 + b0 * (p0 - p1) + b2 * (p2 - p1);
  else
    sp.p = p2 + b0 * (p0 - p2) + b1 * (p1 - p2);
  Vec3 n = glm::cross(p1 - p0, p2 - p0);
  float len = glm::length(n);
  n = len > 0.f ? n / len : Vec3(0, 0, 1);
  if (!m.normals.empty()) {
    Vec3 ns = b0 * m.normals[t.x] + b1 * m.normals[t.y] + b2 * m.normals[t.z];
    float l2 = glm::dot(ns, ns);
    ns = l2 > 0.f ? ns / std::sqrt(l2) : n;
    if (glm::dot(n, ns) < 0.f) n = -n;
    sp.ns = ns;
  } else {
    if (m.flip_normal) n = -n;
    sp.ns = n;
  }
  sp.ng = n;
  // Without uvs, pbrt-v4 gives a triangle's vertices (0,0), (1,0), (1,1),
  // and a quad (a bilinear patch there) its own (u, v): (a c d), the
  // quad's second triangle, is (0,0), (1,1), (0,1).
  if (m.uvs.empty()) sp.uv = !m.quads.empty() && (prim & 1) ? Vec2(b1, b1 + b2) : Vec2(b1 + b2, b2);
  else sp.uv = b0 * m.uvs[t.x] + b1 * m.uvs[t.y] + b2 * m.uvs[t.z];
  sp.error_scale = max_num(max_abs_component(sp.p),
                             max_num(max_abs_component(p0), max_num(max_abs_component(p1), max_abs_component(p2))));
  return sp;
}

inline float triangle_area(const TriangleMesh& m, uint32_t prim) {
  const glm::uvec3 t = m.triangle(prim);
  return 0.5f * glm::length(glm::cross(m.positions[t.y] - m.positions[t.x], m.positions[t.z] - m.positions[t.x]));
}

// `p` is any point near the surface; it is projected onto the sphere.
// The point of the sphere whose outward unit normal is n. Prefer it to
// sphere_point whenever n is known more precisely than a position: for a
// sphere far smaller than its distance from the origin (a 1e-5 light at
// 1e4), p - center keeps almost none of its bits.
inline SurfacePoint sphere_point_at_normal(const Sphere& s, const Vec3& n) {
  SurfacePoint sp;
  sp.p = s.center + s.radius * n;
  sp.ng = sp.ns = s.flip_normal ? -n : n;
  Vec3 dl = glm::mat3(s.object_from_world) * n;  // direction in the sphere's own frame
  float len = glm::length(dl);
  dl = len > 0.f ? dl / len : Vec3(0, 0, 1);
  float phi = std::atan2(dl.y, dl.x);
  if (phi < 0.f) phi += 2.f * kPi;
  sp.uv = Vec2(phi * kInv2Pi, (std::acos(glm::clamp(dl.z, -1.f, 1.f)) - kPi) / -kPi);
  sp.error_scale = max_abs_component(s.center) + s.radius;
  return sp;
}

inline SurfacePoint sphere_point(const Sphere& s, const Vec3& p) {
  Vec3 d = p - s.center;
  float len = glm::length(d);
  return sphere_point_at_normal(s, len > 0.f ? d / len : Vec3(0, 0, 1));
}

// The point of a quadric at surface coordinates uv, in the space the
// quadric is placed in.
inline SurfacePoint quadric_point(const Quadric& q, Vec2 uv) {
  const Vec3 po = quadric_object_point(q, uv);
  SurfacePoint sp;
  sp.p = Vec3(q.world_from_object * glm::dvec4(po, 1.0));
  Vec3 n = q.normal_to_world * quadric_object_normal(q, po);
  float len = glm::length(n);
  n = len > 0.f ? n / len : Vec3(0, 0, 1);
  sp.ng = sp.ns = q.flip_normal ? -n : n;
  sp.uv = uv;
  sp.error_scale = max_num(max_abs_component(sp.p), q.error_scale);
  return sp;
}

// Offsets a ray origin off the surface along the geometric normal, on the
// side `w` (unit) leaves towards. The offset is relative to the magnitude of
// the coordinates, so a scene scaled by 1e-4 or 1e5 behaves alike.
//
// The origin also steps back along w by half the offset. A point on the
// edge where two surfaces meet (a wall's top against a ceiling, rounded
// onto the ceiling's plane) moved only along its own normal would start
// its ray exactly on the other surface, which the ray then need not hit:
// light leaked through a closed room's corner that way
// (tests/extremes_test.cpp, ScaleInvariance). Stepping back puts it
// behind that surface; it stays at least half the offset in front of its
// own.
//
// A negative error_scale marks a curve (curve_error_scale): its offset is
// the fibre's width, not a rounding error, and stepping back by half of it
// would carry a ray that leaves a hair's root back under the skin.
inline constexpr float kRayOffsetScale = 1.0e-5f;
inline Vec3 offset_ray_origin(const Vec3& p, const Vec3& ng, float error_scale, const Vec3& w) {
  float d = kRayOffsetScale * std::fabs(error_scale);
  Vec3 o = glm::dot(w, ng) < 0.f ? p - d * ng : p + d * ng;
  return error_scale > 0.f ? o - (0.5f * d) * w : o - (0.5f * kRayOffsetScale * max_abs_component(p)) * w;
}

}  // namespace lantern
