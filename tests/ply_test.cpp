// The PLY reader: ASCII and binary of both byte orders, quads, and clear
// errors for wrong headers, truncated data and inconsistent counts.
#include <gtest/gtest.h>

#include <cstring>

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

void expect_error(const std::string& data, const char* fragment) {
  try {
    parse_ply(data, "bad.ply");
    ADD_FAILURE() << "no error, expected: " << fragment;
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("bad.ply"), std::string::npos) << e.what();
  }
}

TEST(Ply, BadFilesGiveClearErrors) {
  expect_error("plx\n", "does not start with \"ply\"");
  expect_error("ply\nformat ascii 1.0\nelement vertex 3\n", "no \"end_header\"");
  expect_error("ply\nformat weird 1.0\nend_header\n", "unknown format");
  expect_error("ply\nformat ascii 1.0\nelement vertex 1\nproperty quaternion x\nend_header\n", "unknown property type");
  std::string quad = binary_quad(false);
  expect_error(quad.substr(0, quad.size() - 6), "ends early");
  expect_error(header("ascii", 3, 1) + "0 0 0 0 0\n1 0 0 1 0\n0 1 0 0 1\n3 0 1 7\n", "refers to vertex 7");
  expect_error(header("binary_little_endian", 2000000000, 1), "claims 2000000000 entries");
  expect_error(header("ascii", 3, 1) + "0 0 0 0 0\n1 0 0 1 0\n", "ends early");
}

}  // namespace
}  // namespace lantern
