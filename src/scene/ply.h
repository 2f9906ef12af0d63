// Reads PLY meshes as pbrt uses them: vertex x y z, optional nx ny nz and
// u v (or s t), faces as vertex_indices lists (triangles and quads; larger
// polygons are fan-split). ASCII and binary of either endianness, optionally
// gzip-compressed. Every malformed file gets an InputError naming the file.
#pragma once

#include <glm/gtc/type_precision.hpp>
#include <string>
#include <vector>

#include "math/common.h"

namespace lantern {

struct PlyMesh {
  std::vector<Vec3> positions;
  std::vector<Vec3> normals;
  std::vector<Vec2> uvs;
  std::vector<glm::uvec3> triangles;  // every face, polygons fan-split
  // The faces that were quads: each entry is the first of the two
  // triangles (v0 v1 v2), (v0 v2 v3) its quad (v0 v1 v2 v3) was split into.
  std::vector<uint32_t> quad_first;
};

PlyMesh read_ply(const std::string& path);
// Parses PLY data already in memory; `name` is used in messages.
PlyMesh parse_ply(const std::string& data, const std::string& name);

}  // namespace lantern
