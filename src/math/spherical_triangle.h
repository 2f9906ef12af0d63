// The directions a triangle subtends from a point: a spherical triangle,
// its solid angle, and directions uniform over it (Arvo 1995, "Stratified
// sampling of spherical triangles", SIGGRAPH '95, section 2, with the
// notation kept: vertices A, B, C, angles alpha, beta, gamma, and c the
// arc from A to B). Next-event estimation samples a triangle light so, and
// the density 1 / (solid angle) no longer varies with the distance to the
// point on the light and the light's cosine there, which sampling by area
// leaves in the estimate (docs/light-sampling.md).
//
// In double precision: the solid angle is the angles' excess over pi, and
// for a small triangle most of each angle cancels.
#pragma once

#include "math/common.h"

namespace lantern {

struct SphericalTriangle {
  glm::dvec3 a, b, c;          // unit directions to the vertices
  double alpha = 0.0;          // the angle at a
  double solid_angle = 0.0;    // alpha + beta + gamma - pi
};

// The spherical triangle of v0, v1, v2 seen from p; solid_angle 0 when it
// is degenerate (p in the triangle's plane, or on a vertex).
SphericalTriangle spherical_triangle(const Vec3& p, const Vec3& v0, const Vec3& v1, const Vec3& v2);

// A direction uniform over the spherical triangle (density 1 / solid_angle);
// u.x chooses the sub-triangle of area u.x * solid_angle, u.y the point
// along the arc from B, so the map is continuous and keeps stratification.
Vec3 sample_spherical_triangle(const SphericalTriangle& t, Vec2 u);

// The point of the unit square sample_spherical_triangle maps to direction
// w (a unit vector inside the triangle): where a density over the square
// is read back from a direction (the cosine warp below).
Vec2 invert_spherical_triangle(const SphericalTriangle& t, const Vec3& w);

// Weights at the square's corners for a bilinear warp before the map
// (math/sampling.h, sample_bilinear): the cosine between the normal n at
// the shading point and the direction each corner maps to ((0, 0) and
// (1, 0) to B, (0, 1) to A, (1, 1) to C), at least 0.01. The warped
// directions' density approximates the cosine the estimate carries, as
// pbrt-v4 and Hart et al. 2020 ("Practical product sampling by fitting
// and composing warps", EGSR) warp a spherical triangle's square.
void cosine_warp_weights(const SphericalTriangle& t, const Vec3& n, float w[4]);

// Where next-event estimation samples a triangle light so: from an
// approximate solid angle (area times cosine over squared distance, at the
// centroid) of 0.1 sr up to an exact one of 6.22 sr (pbrt-v4's upper bound:
// beyond it the triangle covers almost a hemisphere and the excess loses
// digits). Below 0.1 sr distance and cosine vary little over the triangle
// and sampling by area, far cheaper, does as well: measured on the shipped
// scenes (docs/light-sampling.md), sampling from 0.01 sr left the same
// error as from 0.1 sr and cost 21-24% of the path tracer's samples per
// second, from 0.1 sr 2-5%.
inline constexpr float kSphericalSamplingFrom = 0.1f;
inline constexpr double kSphericalSamplingTo = 6.22;
inline bool samples_spherical(const SphericalTriangle& t) {
  return t.solid_angle > 0.0 && t.solid_angle <= kSphericalSamplingTo;
}

}  // namespace lantern
