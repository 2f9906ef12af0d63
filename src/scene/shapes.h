// Geometry component pools. Each Shape directive becomes an entity whose
// geometry lives in exactly one pool; the Embree geometry ID indexes the
// `geometries` table, which points into the pools: a table lookup, no
// virtual call.
#pragma once

#include <glm/gtc/type_precision.hpp>
#include <vector>

#include "material/material.h"
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

struct Sphere {
  Vec3 center;
  float radius;
  bool flip_normal;
  Mat4 object_from_world;  // for (u, v): pbrt's parameterisation is in object space
};

enum class ShapeKind : uint8_t { Mesh, Sphere };

struct Geometry {
  ShapeKind kind;
  uint32_t index;            // into meshes or spheres
  MaterialHandle material;
  int32_t light_offset = -1;  // area light of primitive i is lights.area[light_offset + i]
};

struct ShapePools {
  std::vector<TriangleMesh> meshes;
  std::vector<Sphere> spheres;
  std::vector<Geometry> geometries;  // indexed by Embree geomID
};

}  // namespace lantern
