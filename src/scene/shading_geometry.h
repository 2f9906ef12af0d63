// The partial derivatives of a surface point that bump and normal maps
// perturb, computed only for hits on materials that have one. pbrt-v4's
// definitions: for triangles dp/du and dp/dv from the (u, v) at the
// vertices (any basis in the plane where those are degenerate); where a mesh
// has per-vertex normals, the shading frame is the interpolated normal with
// dp/du made orthogonal to it (unit length, as pbrt-v4 leaves it) and dn/du,
// dn/dv from the normals; for spheres the analytic derivatives of pbrt's
// (phi, theta) parameterisation, dn/du and dn/dv from the Weingarten
// equations; for the other quadrics likewise.
#pragma once

#include "scene/surface.h"

namespace lantern {

struct ShadingGeometry {
  Vec3 n;           // shading normal
  Vec3 dpdu, dpdv;  // shading tangents
  Vec3 dndu{0.f}, dndv{0.f};
};

inline ShadingGeometry triangle_shading_geometry(const TriangleMesh& m, uint32_t prim, const SurfacePoint& sp) {
  const glm::uvec3 t = m.triangles[prim];
  const Vec3 &p0 = m.positions[t.x], &p1 = m.positions[t.y], &p2 = m.positions[t.z];
  Vec2 uv0(0, 0), uv1(1, 0), uv2(1, 1);
  if (!m.uvs.empty()) uv0 = m.uvs[t.x], uv1 = m.uvs[t.y], uv2 = m.uvs[t.z];
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
  // The shading frame of a mesh with normals: unit tangents around ns.
  Vec3 ss = g.dpdu, ts = glm::cross(sp.ns, ss);
  if (glm::dot(ts, ts) > 0.f) {
    ss = glm::cross(ts, sp.ns);
  } else {
    coordinate_system(sp.ns, ss, ts);
  }
  g.dpdu = glm::normalize(ss);
  g.dpdv = glm::normalize(ts);
  Vec3 dn1 = m.normals[t.x] - m.normals[t.z], dn2 = m.normals[t.y] - m.normals[t.z];
  if (!degenerate) {
    float inv = 1.f / det;
    g.dndu = (duv12.y * dn1 - duv02.y * dn2) * inv;
    g.dndv = (duv02.x * dn2 - duv12.x * dn1) * inv;
  }
  return g;
}

// dn/du and dn/dv of a surface from its first and second derivatives (the
// Weingarten equations); `fallback` is the normal where dp/du x dp/dv
// vanishes.
inline void weingarten(const Vec3& dpdu, const Vec3& dpdv, const Vec3& d2uu, const Vec3& d2uv, const Vec3& d2vv,
                       const Vec3& fallback, Vec3* dndu, Vec3* dndv) {
  float E = glm::dot(dpdu, dpdu), F = glm::dot(dpdu, dpdv), G = glm::dot(dpdv, dpdv);
  Vec3 cr = glm::cross(dpdu, dpdv);
  float cl = glm::length(cr);
  Vec3 n = cl > 0.f ? cr / cl : fallback;
  float e = glm::dot(n, d2uu), f = glm::dot(n, d2uv), g = glm::dot(n, d2vv);
  float egf2 = E * G - F * F, inv = egf2 != 0.f ? 1.f / egf2 : 0.f;
  *dndu = (f * F - e * G) * inv * dpdu + (e * F - f * E) * inv * dpdv;
  *dndv = (g * F - f * G) * inv * dpdu + (f * F - g * E) * inv * dpdv;
}

inline ShadingGeometry sphere_shading_geometry(const Sphere& s, const SurfacePoint& sp) {
  // In the sphere's own space, where pbrt's (u, v) are defined.
  const glm::mat3 obj_from_world(s.object_from_world);
  const glm::mat3 world_from_obj = glm::inverse(obj_from_world);
  Vec3 p = obj_from_world * (sp.p - s.center);
  float r = glm::length(p);
  ShadingGeometry g;
  g.n = sp.ns;
  if (!(r > 0.f)) {
    coordinate_system(sp.ns, g.dpdu, g.dpdv);
    return g;
  }
  const float phi_max = 2.f * kPi, theta_range = -kPi;  // theta from pi (zmin) to 0 (zmax)
  float zr = std::sqrt(p.x * p.x + p.y * p.y);
  float cos_phi = zr > 0.f ? p.x / zr : 1.f, sin_phi = zr > 0.f ? p.y / zr : 0.f;
  float sin_theta = safe_sqrt(1.f - sqr(p.z / r));
  Vec3 dpdu(-phi_max * p.y, phi_max * p.x, 0.f);
  Vec3 dpdv = theta_range * Vec3(p.z * cos_phi, p.z * sin_phi, -r * sin_theta);
  Vec3 d2uu = -phi_max * phi_max * Vec3(p.x, p.y, 0.f);
  Vec3 d2uv = theta_range * p.z * phi_max * Vec3(-sin_phi, cos_phi, 0.f);
  Vec3 d2vv = -theta_range * theta_range * p;
  Vec3 dndu, dndv;
  weingarten(dpdu, dpdv, d2uu, d2uv, d2vv, p / r, &dndu, &dndv);
  const glm::mat3 normal_to_world = glm::transpose(obj_from_world);  // inverse transpose of world_from_obj
  g.dpdu = world_from_obj * dpdu;
  g.dpdv = world_from_obj * dpdv;
  g.dndu = normal_to_world * dndu;
  g.dndv = normal_to_world * dndv;
  if (glm::dot(glm::cross(g.dpdu, g.dpdv), glm::cross(g.dpdu, g.dpdv)) == 0.f) coordinate_system(sp.ns, g.dpdu, g.dpdv);
  return g;
}

// pbrt's derivatives of its quadrics' (u, v) parameterisations, in object
// space, carried to the space the quadric is placed in.
inline ShadingGeometry quadric_shading_geometry(const Quadric& q, const SurfacePoint& sp) {
  const Vec3 p = quadric_object_point(q, sp.uv);
  const float phi_max = q.phi_max;
  Vec3 dpdu(-phi_max * p.y, phi_max * p.x, 0.f), dpdv(0.f), d2uu(0.f), d2uv(0.f), d2vv(0.f);
  switch (q.kind) {
    case QuadricKind::Sphere: {
      const float r = q.radius, theta_range = q.theta_z_max - q.theta_z_min;
      float zr = std::sqrt(p.x * p.x + p.y * p.y);
      float cos_phi = zr > 0.f ? p.x / zr : 1.f, sin_phi = zr > 0.f ? p.y / zr : 0.f;
      float sin_theta = safe_sqrt(1.f - sqr(p.z / r));
      dpdv = theta_range * Vec3(p.z * cos_phi, p.z * sin_phi, -r * sin_theta);
      d2uu = -phi_max * phi_max * Vec3(p.x, p.y, 0.f);
      d2uv = theta_range * p.z * phi_max * Vec3(-sin_phi, cos_phi, 0.f);
      d2vv = -theta_range * theta_range * p;
      break;
    }
    case QuadricKind::Cylinder:
      dpdv = Vec3(0.f, 0.f, q.z_max - q.z_min);
      d2uu = -phi_max * phi_max * Vec3(p.x, p.y, 0.f);
      break;
    case QuadricKind::Disk: {
      float r = std::sqrt(p.x * p.x + p.y * p.y);
      dpdv = r > 0.f ? Vec3(p.x, p.y, 0.f) * ((q.inner_radius - q.radius) / r) : Vec3(q.inner_radius - q.radius, 0, 0);
      break;
    }
  }
  Vec3 dndu, dndv;
  weingarten(dpdu, dpdv, d2uu, d2uv, d2vv, quadric_object_normal(q, p), &dndu, &dndv);
  ShadingGeometry g;
  g.n = sp.ns;
  g.dpdu = q.linear * dpdu;
  g.dpdv = q.linear * dpdv;
  g.dndu = q.normal_to_world * dndu;
  g.dndv = q.normal_to_world * dndv;
  if (glm::dot(glm::cross(g.dpdu, g.dpdv), glm::cross(g.dpdu, g.dpdv)) == 0.f) coordinate_system(sp.ns, g.dpdu, g.dpdv);
  return g;
}

}  // namespace lantern
