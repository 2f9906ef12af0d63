// The two shapes Embree traces as its own primitives: triangle meshes and
// spheres, as the scene stores them (in world space).
#pragma once

#include <glm/gtc/type_precision.hpp>
#include <vector>

#include "math/common.h"

namespace lantern {

struct TriangleMesh {
  // World-space positions. Embree reads 16 bytes per vertex, so the vector
  // carries one padding element past `vertex_count`.
  std::vector<Vec3> positions;
  std::vector<glm::uvec3> triangles;
  std::vector<Vec3> normals;  // empty, or one per vertex (already flipped by ReverseOrientation)
  std::vector<Vec2> uvs;      // empty, or one per vertex
  uint32_t vertex_count = 0;
  bool flip_normal = false;  // ReverseOrientation xor a handedness-swapping transform (meshes without N)
};

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
