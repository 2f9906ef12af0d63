// The two shapes Embree traces as its own primitives: triangle meshes and
// spheres, as the scene stores them (in world space).
#pragma once

#include <glm/gtc/type_precision.hpp>
#include <vector>

#include "math/common.h"

namespace lantern {

// A mesh of triangles, or of parallelograms kept as quads: quad q = (a b c
// d), read around its face, is triangles 2q = (a b c) and 2q + 1 = (a c d),
// which is how every reader of the mesh sees it (triangle(i)). Embree
// traces the quads as its own quad primitive on the same index array: half
// the primitives, two thirds of the indices (docs/performance.md,
// "Production scale"), and a hit on quad q at Embree's (u, v) is carried to
// its triangle by quad_hit_triangle.
struct TriangleMesh {
  // World-space positions. Embree reads 16 bytes per vertex, so the vector
  // carries one padding element past `vertex_count`.
  std::vector<Vec3> positions;
  std::vector<glm::uvec3> triangles;  // empty when the mesh is quads
  std::vector<glm::uvec4> quads;      // empty when it is triangles
  std::vector<Vec3> normals;  // empty, or one per vertex (already flipped by ReverseOrientation)
  std::vector<Vec2> uvs;      // empty, or one per vertex
  uint32_t vertex_count = 0;
  bool flip_normal = false;  // ReverseOrientation xor a handedness-swapping transform (meshes without N)

  size_t triangle_count() const { return triangles.size() + 2 * quads.size(); }
  glm::uvec3 triangle(size_t i) const {
    if (quads.empty()) return triangles[i];
    const glm::uvec4 q = quads[i >> 1];
    return i & 1 ? glm::uvec3(q.x, q.z, q.w) : glm::uvec3(q.x, q.y, q.z);
  }
};

// Embree's hit on quad q of a parallelogram mesh at (u, v) (its point is
// a + u (b - a) + v (d - a)) as the triangle and barycentrics (b1, b2) of
// the same point: (a b c) where u >= v, (a c d) elsewhere, since
// d - a = c - b.
inline uint32_t quad_hit_triangle(uint32_t q, float u, float v, float* b1, float* b2) {
  if (u >= v) {
    *b1 = u - v, *b2 = v;
    return 2 * q;
  }
  *b1 = u, *b2 = v - u;
  return 2 * q + 1;
}

// Two triangles a cell of an nu x nv grid of vertices (u fastest), split
// along the cell's (i, j)-(i+1, j+1) diagonal, as pbrt-v3 dices its
// heightfields and NURBS.
inline void add_grid_triangles(TriangleMesh& m, int nu, int nv) {
  const auto at = [nu](int i, int j) { return uint32_t(j * nu + i); };
  for (int j = 0; j + 1 < nv; ++j)
    for (int i = 0; i + 1 < nu; ++i) {
      m.triangles.emplace_back(at(i, j), at(i + 1, j), at(i + 1, j + 1));
      m.triangles.emplace_back(at(i, j), at(i + 1, j + 1), at(i, j + 1));
    }
}

struct Sphere {
  Vec3 center;
  float radius;
  bool flip_normal;
  Mat4 object_from_world;  // for (u, v): pbrt's parameterisation is in object space
};

}  // namespace lantern
