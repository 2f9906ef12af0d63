// The PLY reader: ASCII and binary of both byte orders, quads, and clear
// errors for wrong headers, truncated data and inconsistent counts.
#include <gtest/gtest.h>

#include <zlib.h>

#include <cstring>
#include <fstream>

#include "lantern/error.h"
#include "scene/ply.h"

namespace lantern {
namespace {

std::string header(const char* format, int nv, int nf) {
  return std::string("ply\nformat ") + format + " 1.0\ncomment test\nelement vertex " + std::to_string(nv) +
         "\nproperty float x\nproperty float y\nproperty float z\nproperty float u\nproperty float v\nelement face " +
         std::to_string(nf) + "\nproperty list uchar int vertex_indices\nend_header\n";
}

template <class T>
void put(std::string& s, T v, bool big_endian) {
  char b[sizeof(T)];
  std::memcpy(b, &v, sizeof(T));
  if (big_endian) std::reverse(b, b + sizeof(T));
  s.append(b, sizeof(T));
}

std::string binary_quad(bool big_endian) {
  std::string s = header(big_endian ? "binary_big_endian" : "binary_little_endian", 4, 1);
  float v[4][5] = {{0, 0, 0, 0, 0}, {1, 0, 0, 1, 0}, {1, 1, 0, 1, 1}, {0, 1, 0, 0, 1}};
  for (auto& row : v)
    for (float f : row) put(s, f, big_endian);
  s += char(4);
  for (int i : {0, 1, 2, 3}) put(s, int32_t(i), big_endian);
  return s;
}

TEST(Ply, AsciiTriangle) {
  PlyMesh m = parse_ply(header("ascii", 3, 1) + "0 0 0 0 0\n1 0 0 1 0\n0 1 0 0 1\n3 0 1 2\n", "a.ply");
  ASSERT_EQ(m.positions.size(), 3u);
  ASSERT_EQ(m.triangles.size(), 1u);
  EXPECT_EQ(m.uvs.size(), 3u);
  EXPECT_TRUE(m.normals.empty());
  EXPECT_EQ(m.positions[1], Vec3(1, 0, 0));
}

TEST(Ply, BinaryBothEndiannessesAndQuads) {
  for (bool be : {false, true}) {
    PlyMesh m = parse_ply(binary_quad(be), "q.ply");
    ASSERT_EQ(m.positions.size(), 4u) << be;
    ASSERT_EQ(m.triangles.size(), 2u) << "a quad is split in two";
    EXPECT_EQ(m.positions[2], Vec3(1, 1, 0));
    EXPECT_EQ(m.uvs[3], Vec2(0, 1));
  }
}

// The bulk path (native byte order, float vertices, byte-count faces) and
// the value-by-value path (the other byte order; a double-precision copy)
// must read the same mesh, polygons included.
TEST(Ply, BulkAndGeneralReadersAgree) {
  const int n = 50;
  for (bool be : {false, true}) {
    for (bool doubles : {false, true}) {
      std::string s = std::string("ply\nformat ") + (be ? "binary_big_endian" : "binary_little_endian") +
                      " 1.0\nelement vertex " + std::to_string(n) + "\nproperty " + (doubles ? "double" : "float") +
                      " x\nproperty float y\nproperty float z\nproperty float nx\nproperty float ny\nproperty float nz\n"
                      "element face " + std::to_string(n - 4) + "\nproperty list uchar uint vertex_indices\nend_header\n";
      for (int i = 0; i < n; ++i) {
        if (doubles) put(s, double(i) * 0.25, be);
        else put(s, float(i) * 0.25f, be);
        for (float f : {float(i % 7), -1.5f * float(i), 0.f, 1.f, 0.f}) put(s, f, be);
      }
      for (int f = 0; f < n - 4; ++f) {
        int count = 3 + f % 3;  // triangles, quads and pentagons
        s += char(count);
        for (int j = 0; j < count; ++j) put(s, uint32_t(f + j), be);
      }
      PlyMesh m = parse_ply(s, "agree.ply");
      SCOPED_TRACE(std::string(be ? "big" : "little") + (doubles ? ", double x" : ", float"));
      ASSERT_EQ(m.positions.size(), size_t(n));
      ASSERT_EQ(m.normals.size(), size_t(n));
      EXPECT_EQ(m.positions[10], Vec3(2.5f, 3.f, -15.f));
      EXPECT_EQ(m.normals[10], Vec3(0.f, 1.f, 0.f));
      size_t expected = 0;
      for (int f = 0; f < n - 4; ++f) expected += size_t(1 + f % 3);
      ASSERT_EQ(m.triangles.size(), expected);
      EXPECT_EQ(m.triangles[2], glm::uvec3(1, 3, 4));  // the quad 1 2 3 4, fan-split
    }
  }
}

// .ply.gz, as pbrt-v4 scenes ship them, reads like the plain file.
TEST(Ply, GzipCompressedFilesRead) {
  const std::string plain = ::testing::TempDir() + "/lantern_quad.ply", packed = plain + ".gz";
  std::string data = binary_quad(false);
  std::ofstream(plain, std::ios::binary) << data;
  gzFile f = gzopen(packed.c_str(), "wb");
  ASSERT_TRUE(f);
  gzwrite(f, data.data(), unsigned(data.size()));
  gzclose(f);
  PlyMesh a = read_ply(plain), b = read_ply(packed);
  EXPECT_EQ(a.positions, b.positions);
  EXPECT_EQ(a.triangles, b.triangles);
  EXPECT_EQ(b.triangles.size(), 2u);
}

void expect_ply_error(const std::string& data, const char* fragment) {
  try {
    parse_ply(data, "bad.ply");
    ADD_FAILURE() << "no error, expected: " << fragment;
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("bad.ply"), std::string::npos) << e.what();
  }
}

TEST(Ply, BadFilesGiveClearErrors) {
  expect_ply_error("plx\n", "does not start with \"ply\"");
  expect_ply_error("ply\nformat ascii 1.0\nelement vertex 3\n", "no \"end_header\"");
  expect_ply_error("ply\nformat weird 1.0\nend_header\n", "unknown format");
  expect_ply_error("ply\nformat ascii 1.0\nelement vertex 1\nproperty quaternion x\nend_header\n", "unknown property type");
  std::string quad = binary_quad(false);
  expect_ply_error(quad.substr(0, quad.size() - 6), "ends early");
  expect_ply_error(header("ascii", 3, 1) + "0 0 0 0 0\n1 0 0 1 0\n0 1 0 0 1\n3 0 1 7\n", "refers to vertex 7");
  expect_ply_error(header("binary_little_endian", 2000000000, 1), "claims 2000000000 entries");
  expect_ply_error(header("ascii", 3, 1) + "0 0 0 0 0\n1 0 0 1 0\n", "ends early");
}

}  // namespace
}  // namespace lantern
