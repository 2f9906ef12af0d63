// pbrt-v3's "nurbs" shape: a non-uniform rational B-spline surface, diced
// into triangles at load as pbrt-v3 dices it (a 30 x 30 grid of points over
// [u0, u1] x [v0, v1], two triangles per cell, normals from the surface's
// tangents, uv the surface parameters). Evaluation by the Cox-de Boor
// recurrence and its derivative (Piegl and Tiller, The NURBS Book, 2nd
// ed., algorithms A2.1-A2.3); a rational surface is the projection of the
// polynomial one in homogeneous coordinates (ibid., eq. 4.15), its
// derivative by the quotient rule (eq. 4.8).
#pragma once

#include <string>
#include <vector>

#include "geometry/triangle_mesh.h"
#include "math/common.h"

namespace lantern {

struct NurbsSurface {
  int nu = 0, nv = 0;          // control points in u and in v
  int uorder = 0, vorder = 0;  // degree + 1
  std::vector<float> uknots, vknots;  // nu + uorder and nv + vorder values, non-decreasing
  // Control points, u fastest (point (i, j) at j * nu + i), in homogeneous
  // coordinates: (w x, w y, w z, w), as pbrt-v3's "Pw" gives them; "P"
  // points have w = 1.
  std::vector<glm::vec4> points;
  float u0 = 0.f, u1 = 0.f, v0 = 0.f, v1 = 0.f;  // the part of the surface made
};

// What is wrong with the surface's numbers, or "" when nothing is: counts
// that do not match, orders below 1, knots that decrease, a range outside
// the knots' valid span or empty, weights not above 0.
std::string nurbs_problem(const NurbsSurface& s);

struct NurbsPoint {
  Vec3 p, dpdu, dpdv;
};
// The surface at (u, v), clamped into its valid range. The surface must
// have no problem.
NurbsPoint evaluate_nurbs(const NurbsSurface& s, double u, double v);

// The dice x dice grid of points and its 2 (dice - 1)^2 triangles, with
// unit normals cross(dpdu, dpdv) (where the tangents vanish, as at a pole,
// the normal a little way into the surface) and uvs (u, v).
TriangleMesh tessellate_nurbs(const NurbsSurface& s, int dice = 30);

}  // namespace lantern
