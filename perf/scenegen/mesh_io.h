// The generator's meshes and their binary PLY files (triangles or quads).
#pragma once

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <vector>

namespace scenegen {

struct V3 {
  float x, y, z;
};

// Faces of `arity` vertices (3: triangles, 4: quads) in one index list.
struct Mesh {
  std::vector<V3> p;
  std::vector<uint32_t> idx;
  uint32_t arity = 3;
  size_t faces() const { return idx.size() / arity; }
};

inline void write_ply(const std::filesystem::path& path, const Mesh& m) {
  std::ofstream f(path, std::ios::binary);
  f << "ply\nformat binary_little_endian 1.0\nelement vertex " << m.p.size()
    << "\nproperty float x\nproperty float y\nproperty float z\nelement face " << m.faces()
    << "\nproperty list uchar uint vertex_indices\nend_header\n";
  f.write(reinterpret_cast<const char*>(m.p.data()), std::streamsize(m.p.size() * sizeof(V3)));
  const size_t rec = 1 + 4 * size_t(m.arity);
  std::vector<char> faces(m.faces() * rec);
  for (size_t t = 0; t < m.faces(); ++t) {
    faces[rec * t] = char(m.arity);
    std::memcpy(&faces[rec * t + 1], &m.idx[m.arity * t], 4 * m.arity);
  }
  f.write(faces.data(), std::streamsize(faces.size()));
  if (!f) throw std::runtime_error("cannot write " + path.string());
}

}  // namespace scenegen
