// The partial derivatives of a surface point that bump and normal maps
// perturb, computed only for hits on materials that have one. pbrt-v4's
// definitions: for triangles dp/du and dp/dv from the (u, v) at the
// vertices (any basis in the plane where those are degenerate); where a mesh
// has per-vertex normals, the shading frame is the interpolated normal with
// dp/du made orthogonal to it (at dp/du's length, as pbrt-v4 leaves it) and
// dn/du, dn/dv from the normals; for spheres the analytic derivatives of pbrt's
// (phi, theta) parameterisation, dn/du and dn/dv from the Weingarten
// equations; for the other quadrics likewise.
#pragma once

#include "geometry/surface.h"

namespace lantern {

struct ShadingGeometry {
  Vec3 n;           // shading normal
  Vec3 dpdu, dpdv;  // shading tangents (pbrt-v4's shading.dpdu, shading.dpdv)
  Vec3 dndu{0.f}, dndv{0.f};
  // A mesh's normals turn dpdu and dpdv around the interpolated normal; the
  // parameterisation's own derivatives (pbrt-v4's SurfaceInteraction::dpdu,
  // dpdv) are then kept here, for the texture footprint, which maps pixel
  // steps to (u, v) through them.
  bool turned = false;
  Vec3 surface_dpdu{0.f}, surface_dpdv{0.f};
  Vec3 uv_dpdu() const { return turned ? surface_dpdu : dpdu; }
  Vec3 uv_dpdv() const { return turned ? surface_dpdv : dpdv; }
};

inline ShadingGeometry triangle_shading_geometry(const TriangleMesh& m, uint32_t prim, const SurfacePoint& sp) {
  const glm::uvec3 t = m.triangle(prim);
  const Vec3 &p0 = m.positions[t.x], &p1 = m.positions[t.y], &p2 = m.positions[t.z];
  Vec2 uv0(0, 0), uv1(1, 0), uv2(1, 1);  // as triangle_point's defaults
  if (!m.uvs.empty()) uv0 = m.uvs[t.x], uv1 = m.uvs[t.y], uv2 = m.uvs[t.z];
  else if (!m.quads.empty() && (prim & 1)) uv1 = Vec2(1, 1), uv2 = Vec2(0, 1);
  Vec2 duv02 = uv0 - uv2, duv12 = uv1 - uv2;
  Vec3 dp02 = p0 - p2, dp12 = p1 - p2;
  float det = duv02.x * duv12.y - duv02.y * duv12.x;
  ShadingGeometry g;
  bool degenerate = std::fabs(det) < 1e-9f;
  if (!degenerate) {
    float inv = 1.f / det;
    g.dpdu = (duv12.y * dp02 - duv02.y * dp12) * inv;
    g.dpdv = (duv02.x * dp12 - duv12.x * dp02) * inv;
  }
  if (degenerate || glm::dot(glm::cross(g.dpdu, g.dpdv), glm::cross(g.dpdu, g.dpdv)) == 0.f)
    coordinate_system(sp.ng, g.dpdu, g.dpdv);
  g.n = sp.ns;
  if (m.normals.empty()) return g;
  // The shading frame of a mesh with normals, as pbrt-v4 builds it: ts =
  // ns x dp/du and ss = ts x ns, left unnormalised, so both have about the
  // length of dp/du (bump and normal maps scale by it).
  Vec3 ss = g.dpdu, ts = glm::cross(sp.ns, ss);
  if (glm::dot(ts, ts) > 0.f) {
    ss = glm::cross(ts, sp.ns);
  } else {
    coordinate_system(sp.ns, ss, ts);
  }
  g.turned = true;
  g.surface_dpdu = g.dpdu;
  g.surface_dpdv = g.dpdv;
  g.dpdu = ss;
  g.dpdv = ts;
  Vec3 dn1 = m.normals[t.x] - m.normals[t.z], dn2 = m.normals[t.y] - m.normals[t.z];
  if (!degenerate) {
    float inv = 1.f / det;
    g.dndu = (duv12.y * dn1 - duv02.y * dn2) * inv;
    g.dndv = (duv02.x * dn2 - duv12.x * dn1) * inv;
  }
  return g;
}

// The first and second derivatives of a surface's (u, v)
// parameterisation at a point.
struct SurfaceDerivatives {
  Vec3 dpdu{0.f}, dpdv{0.f}, d2uu{0.f}, d2uv{0.f}, d2vv{0.f};
};

// pbrt's sphere parameterisation at object-space point p of a sphere of
// radius r: phi = u * phi_max, theta = theta(zmin) + v * theta_range.
inline SurfaceDerivatives sphere_derivatives(const Vec3& p, float r, float phi_max, float theta_range) {
  float zr = std::sqrt(p.x * p.x + p.y * p.y);
  float cos_phi = zr > 0.f ? p.x / zr : 1.f, sin_phi = zr > 0.f ? p.y / zr : 0.f;
  float sin_theta = safe_sqrt(1.f - sqr(p.z / r));
  SurfaceDerivatives d;
  d.dpdu = Vec3(-phi_max * p.y, phi_max * p.x, 0.f);
  d.dpdv = theta_range * Vec3(p.z * cos_phi, p.z * sin_phi, -r * sin_theta);
  d.d2uu = -phi_max * phi_max * Vec3(p.x, p.y, 0.f);
  d.d2uv = theta_range * p.z * phi_max * Vec3(-sin_phi, cos_phi, 0.f);
  d.d2vv = -theta_range * theta_range * p;
  return d;
}

// The shading geometry of object-space derivatives d (dn/du and dn/dv from
// the Weingarten equations; `fallback` is the normal where dp/du x dp/dv
// vanishes), carried to the placed space by the linear map and its
// inverse transpose.
inline ShadingGeometry placed_shading_geometry(const SurfaceDerivatives& d, const Vec3& fallback,
                                               const glm::mat3& linear, const glm::mat3& normal_to_world,
                                               const Vec3& ns) {
  float E = glm::dot(d.dpdu, d.dpdu), F = glm::dot(d.dpdu, d.dpdv), G = glm::dot(d.dpdv, d.dpdv);
  Vec3 cr = glm::cross(d.dpdu, d.dpdv);
  float cl = glm::length(cr);
  Vec3 n = cl > 0.f ? cr / cl : fallback;
  float e = glm::dot(n, d.d2uu), f = glm::dot(n, d.d2uv), g2 = glm::dot(n, d.d2vv);
  float egf2 = E * G - F * F, inv = egf2 != 0.f ? 1.f / egf2 : 0.f;
  Vec3 dndu = (f * F - e * G) * inv * d.dpdu + (e * F - f * E) * inv * d.dpdv;
  Vec3 dndv = (g2 * F - f * G) * inv * d.dpdu + (f * F - g2 * E) * inv * d.dpdv;
  ShadingGeometry g;
  g.n = ns;
  g.dpdu = linear * d.dpdu;
  g.dpdv = linear * d.dpdv;
  g.dndu = normal_to_world * dndu;
  g.dndv = normal_to_world * dndv;
  if (glm::dot(glm::cross(g.dpdu, g.dpdv), glm::cross(g.dpdu, g.dpdv)) == 0.f) coordinate_system(ns, g.dpdu, g.dpdv);
  return g;
}

inline ShadingGeometry sphere_shading_geometry(const Sphere& s, const SurfacePoint& sp) {
  // In the sphere's own space, where pbrt's (u, v) are defined.
  const glm::mat3 obj_from_world(s.object_from_world);
  Vec3 p = obj_from_world * (sp.p - s.center);
  float r = glm::length(p);
  if (!(r > 0.f)) {
    ShadingGeometry g;
    g.n = sp.ns;
    coordinate_system(sp.ns, g.dpdu, g.dpdv);
    return g;
  }
  // theta runs from pi (zmin) to 0 (zmax); the inverse transpose of
  // world_from_obj is the transpose of obj_from_world.
  return placed_shading_geometry(sphere_derivatives(p, r, 2.f * kPi, -kPi), p / r, glm::inverse(obj_from_world),
                                 glm::transpose(obj_from_world), sp.ns);
}

// pbrt's derivatives of its quadrics' (u, v) parameterisations, in object
// space, carried to the space the quadric is placed in.
inline ShadingGeometry quadric_shading_geometry(const Quadric& q, const SurfacePoint& sp) {
  const Vec3 p = quadric_object_point(q, sp.uv);
  SurfaceDerivatives d;
  switch (q.kind) {
    case QuadricKind::Sphere: d = sphere_derivatives(p, q.radius, q.phi_max, q.theta_z_max - q.theta_z_min); break;
    case QuadricKind::Cylinder:
      d.dpdu = Vec3(-q.phi_max * p.y, q.phi_max * p.x, 0.f);
      d.dpdv = Vec3(0.f, 0.f, q.z_max - q.z_min);
      d.d2uu = -q.phi_max * q.phi_max * Vec3(p.x, p.y, 0.f);
      break;
    case QuadricKind::Disk: {
      float r = std::sqrt(p.x * p.x + p.y * p.y);
      d.dpdu = Vec3(-q.phi_max * p.y, q.phi_max * p.x, 0.f);
      d.dpdv = r > 0.f ? Vec3(p.x, p.y, 0.f) * ((q.inner_radius - q.radius) / r) : Vec3(q.inner_radius - q.radius, 0, 0);
      break;
    }
  }
  return placed_shading_geometry(d, quadric_object_normal(q, p), q.linear, q.normal_to_world, sp.ns);
}

// A bilinear patch's derivatives in (u, v), dn/du and dn/dv from the
// Weingarten equations (its only second derivative is d2p/dudv), or from
// the interpolated normals when the set has them; with texture
// coordinates, carried to (s, t) through the inverse of d(s, t)/d(u, v).
inline ShadingGeometry bilinear_shading_geometry(const BilinearPatchSet& s, uint32_t i, Vec2 uv, const SurfacePoint& sp) {
  const PatchCorners c = patch_corners(s, i);
  SurfaceDerivatives d;
  d.dpdu = glm::mix(c.p10 - c.p00, c.p11 - c.p01, uv.y);
  d.dpdv = glm::mix(c.p01 - c.p00, c.p11 - c.p10, uv.x);
  d.d2uv = (c.p00 - c.p01) + (c.p11 - c.p10);
  ShadingGeometry g = placed_shading_geometry(d, sp.ng, glm::mat3(1.f), glm::mat3(1.f), sp.ns);
  const glm::uvec4 v = s.patches[i];
  if (!s.normals.empty()) {
    g.dndu = glm::mix(s.normals[v.y] - s.normals[v.x], s.normals[v.w] - s.normals[v.z], uv.y);
    g.dndv = glm::mix(s.normals[v.z] - s.normals[v.x], s.normals[v.w] - s.normals[v.y], uv.x);
  }
  Vec2 st[4];
  if (!patch_corner_uvs(s, i, st)) return g;
  const Vec2 dst_du = glm::mix(st[1] - st[0], st[3] - st[2], uv.y);
  const Vec2 dst_dv = glm::mix(st[2] - st[0], st[3] - st[1], uv.x);
  const float det = dst_du.x * dst_dv.y - dst_du.y * dst_dv.x;
  if (!(std::fabs(det) > 1e-12f)) return g;
  // (du, dv) per (ds, dt): the inverse of [dst_du dst_dv].
  const float du_ds = dst_dv.y / det, du_dt = -dst_dv.x / det, dv_ds = -dst_du.y / det, dv_dt = dst_du.x / det;
  const ShadingGeometry in_uv = g;
  g.dpdu = in_uv.dpdu * du_ds + in_uv.dpdv * dv_ds;
  g.dpdv = in_uv.dpdu * du_dt + in_uv.dpdv * dv_dt;
  g.dndu = in_uv.dndu * du_ds + in_uv.dndv * dv_ds;
  g.dndv = in_uv.dndu * du_dt + in_uv.dndv * dv_dt;
  if (glm::dot(glm::cross(g.dpdu, g.dpdv), glm::cross(g.dpdu, g.dpdv)) == 0.f) coordinate_system(sp.ns, g.dpdu, g.dpdv);
  return g;
}

// A curve's dp/du along the whole curve's u, and dp/dv across its width
// (pbrt's v runs over the width); a ribbon does not bend across, so the
// normal's derivatives are left at zero.
inline ShadingGeometry curve_shading_geometry(const CurveSet& c, uint32_t segment, float u, const SurfacePoint& sp) {
  const CurveFrame f = curve_eval(c, segment, u);
  const Vec2 span = c.u_range[segment];
  ShadingGeometry g;
  g.n = sp.ns;
  g.dpdu = f.dpdu / max_num(span.y - span.x, 1e-30f);
  g.dpdv = (2.f * f.radius) * glm::cross(sp.ns, sp.dpdu);
  if (glm::dot(glm::cross(g.dpdu, g.dpdv), glm::cross(g.dpdu, g.dpdv)) == 0.f) coordinate_system(sp.ns, g.dpdu, g.dpdv);
  return g;
}

}  // namespace lantern
