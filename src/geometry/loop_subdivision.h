// pbrt's Shape "loopsubdiv": Loop subdivision (Loop 1987) of a triangle
// mesh, refined at load to `levels` levels and pushed to the limit surface,
// with normals from the limit tangents, as pbrt-v4 does.
//
// Rules (C. Loop, "Smooth Subdivision Surfaces Based on Triangles", 1987;
// the vertex weight beta as simplified by Warren, 3/16 at valence 3 and
// 3/(8n) above):
//   interior vertex  (1 - n beta) v + beta sum(ring)
//   boundary vertex  3/4 v + 1/8 (both boundary neighbours)
//   interior edge    3/8 (ends) + 1/8 (the two opposite vertices)
//   boundary edge    1/2 (ends)
// Limit positions and the boundary tangent masks follow Hoppe et al.,
// "Piecewise Smooth Surface Reconstruction", SIGGRAPH 1994. Like pbrt, no
// crease tags: every boundary is a crease, every interior edge is smooth.
//
// Orientation follows pbrt-v4: a vertex's one-ring is walked so that the
// limit normal S x T points against the winding normal of the faces
// (cross(p1 - p0, p2 - p0)); the mesh then faces its normals, as every mesh
// with normals does.
#pragma once

#include <glm/gtc/type_precision.hpp>
#include <stdexcept>
#include <vector>

#include "math/common.h"

namespace lantern {

struct SubdividedMesh {
  std::vector<Vec3> positions;  // on the limit surface
  std::vector<Vec3> normals;    // the limit surface's, not normalised
  std::vector<glm::uvec3> triangles;
};

// The largest number of triangles a subdivision may produce (about 3 GiB of
// vertices, normals and indices); a file asking for more is refused before
// anything is allocated.
constexpr uint64_t kMaxSubdividedTriangles = uint64_t(1) << 27;

// Throws std::invalid_argument, saying what is wrong, for an index out of
// range, a triangle that repeats a vertex, an edge shared by more than two
// triangles or by two that run along it the same way (orientations that
// disagree), a vertex where separate fans
// of triangles meet, and a refinement larger than kMaxSubdividedTriangles.
SubdividedMesh loop_subdivide(const std::vector<Vec3>& P, const std::vector<int>& indices, int levels);

}  // namespace lantern
