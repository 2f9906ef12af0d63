// The guiding trees' look-ups read a point's binary digits from an integer
// (math/binary_digits.h) where they used to halve it in float: the digits
// and the spatial tree's leaves must be the ones halving finds, on split
// planes, bounds and outside them too; a directional tree's cell and
// density must be constant over each cell, whose lower edges belong to it
// and upper edges to the next. (That the quadrants are the ones its draws
// land in, DirectionalTree.DensityIntegratesToOneAndMatchesItsSamples
// holds: with x and y swapped it fails.)
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <random>
#include <stdexcept>
#include <vector>

#include "guiding/directional_tree.h"
#include "guiding/spatial_nodes.h"
#include "math/binary_digits.h"
#include "math/state_io.h"

using namespace lantern;

namespace {

// What a tree that halves [0, 1] finds: digit k is whether c, rescaled k
// times, lies in the upper half.
uint32_t digits_by_halving(float c) {
  c = std::min(std::max(c, 0.f), 1.f);
  uint32_t d = 0;
  for (int k = 0; k < 32; ++k) {
    const bool upper = c >= 0.5f;
    c = upper ? 2.f * c - 1.f : 2.f * c;
    d |= uint32_t(upper) << (31 - k);
  }
  return d;
}

// The spatial leaf as halving in float finds it, the axis from each node.
uint32_t leaf_by_halving(const std::vector<SpatialNode>& nodes, const SpatialCube& cube, const Vec3& p) {
  Vec3 q = glm::clamp((p - cube.lo) / cube.extent, 0.f, 1.f);
  uint32_t n = 0;
  for (;;) {
    const SpatialNode& node = nodes[n];
    if (node.child[0] == 0) return node.leaf;
    float& c = q[node.axis];
    const bool upper = c >= 0.5f;
    c = upper ? 2.f * c - 1.f : 2.f * c;
    n = node.child[upper ? 1 : 0];
  }
}

struct TestLeaf {
  uint64_t records = 0;
  Vec3 size{0.f};
};

float bits_to_float(uint32_t b) {
  float f;
  std::memcpy(&f, &b, sizeof f);
  return f;
}

}  // namespace

TEST(GuidingLookup, DigitsAreTheOnesHalvingFinds) {
  std::mt19937 rng(5);
  std::vector<float> values = {0.f,
                               -0.f,
                               1.f,
                               0.5f,
                               0.25f,
                               0.75f,
                               std::nextafter(1.f, 0.f),
                               std::nextafter(0.5f, 0.f),
                               0x1p-8f,
                               std::nextafter(0x1p-8f, 0.f),
                               0x1p-32f,
                               0x1p-33f,
                               1e-38f,
                               1e-45f,
                               -1.f,
                               2.f,
                               std::numeric_limits<float>::infinity()};
  // Every exponent of [0, 1), with random mantissas, and plain uniforms.
  for (int i = 0; i < 400000; ++i) {
    const uint32_t exponent = 1 + rng() % 126;  // 2^-126 .. 2^-1
    values.push_back(bits_to_float(exponent << 23 | (rng() & 0x7FFFFF)));
    values.push_back(std::uniform_real_distribution<float>(0.f, 1.f)(rng));
  }
  for (float c : values) ASSERT_EQ(binary_digits(c), digits_by_halving(c)) << c;
  EXPECT_EQ(binary_digits(std::numeric_limits<float>::quiet_NaN()), 0u);
}

TEST(GuidingLookup, SpatialLeavesAreTheOnesHalvingFinds) {
  // A tree grown by records around a few points, deep near them (down to
  // the limit split_spatial_leaf keeps), and points on its split planes,
  // its bounds and outside them as well as anywhere.
  const SpatialCube cube = SpatialCube::around(Vec3(-3.f, 0.5f, -1.f), Vec3(4.f, 2.f, 7.f));
  std::vector<SpatialNode> nodes{SpatialNode{}};
  std::vector<TestLeaf> leaves{TestLeaf{0, Vec3(cube.extent)}};
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> u(0.f, 1.f);
  const Vec3 centres[3] = {Vec3(0.1f, 1.f, 2.f), Vec3(3.9f, 1.9f, 6.9f), Vec3(-3.f, 0.5f, -1.f)};
  for (int round = 0; round < 6; ++round) {
    for (int i = 0; i < 30000; ++i) {
      const Vec3 p = centres[i % 3] + (Vec3(u(rng), u(rng), u(rng)) - 0.5f) * std::ldexp(1.f, -2 * round);
      ++leaves[spatial_leaf_of(nodes, cube, p)].records;
    }
    const size_t count = nodes.size();
    for (uint32_t n = 0; n < count; ++n)
      if (nodes[n].child[0] == 0) split_spatial_leaf(nodes, leaves, n, 1000, cube, size_t(1) << 16);
    for (TestLeaf& l : leaves) l.records = 0;
  }
  ASSERT_GT(leaves.size(), 200u);
  std::vector<Vec3> points;
  for (int i = 0; i < 200000; ++i) {
    // Anywhere in and around the cube, near the centres, and on dyadic
    // planes of the cube (split planes of every depth).
    points.push_back(cube.lo + (Vec3(u(rng), u(rng), u(rng)) * 1.2f - 0.1f) * cube.extent);
    points.push_back(centres[i % 3] + (Vec3(u(rng), u(rng), u(rng)) - 0.5f) * 1e-3f);
    const int depth = 1 + int(rng() % 20);
    Vec3 q(u(rng), u(rng), u(rng));
    q[int(rng() % 3)] = std::ldexp(float(rng() % (1u << depth)), -depth);
    points.push_back(cube.lo + q * cube.extent);
  }
  for (const Vec3& p : points)
    ASSERT_EQ(spatial_leaf_of(nodes, cube, p), leaf_by_halving(nodes, cube, p)) << p.x << " " << p.y << " " << p.z;
  // A NaN position still finds a leaf.
  EXPECT_LT(spatial_leaf_of(nodes, cube, Vec3(std::nanf(""), 1.f, 1.f)), leaves.size());

  // Trees are read back only if their axes alternate from x, as the
  // look-up reads them.
  StringWriter out;
  write_spatial_nodes(out, nodes);
  out.put(uint64_t(leaves.size()));
  std::string bytes = out.bytes + std::string(leaves.size(), '\0');
  uint64_t read_leaves = 0;
  StringReader in(bytes);
  EXPECT_EQ(read_spatial_nodes(in, 1, &read_leaves, "a tree").size(), nodes.size());
  std::vector<SpatialNode> turned = nodes;
  turned[1].axis = 2;  // the root's first child splits z instead of y
  StringWriter bad;
  write_spatial_nodes(bad, turned);
  bad.put(uint64_t(leaves.size()));
  const std::string bad_bytes = bad.bytes + std::string(leaves.size(), '\0');
  StringReader bad_in(bad_bytes);
  EXPECT_THROW(read_spatial_nodes(bad_in, 1, &read_leaves, "a tree"), std::runtime_error);
}

TEST(GuidingLookup, DirectionalCellsAndDensitiesAreTheOnesOfTheirSquares) {
  // A tree refined where energy was put, 8 levels deep: on a grid of 2^10
  // square cells, each coarse enough to lie in one of its cells, every
  // point of a grid cell, its lower corner included, must find the cell
  // and density its centre finds; its upper edges belong to the next.
  DirectionalTree t;
  std::mt19937 rng(2);
  std::uniform_real_distribution<float> u(0.f, 1.f);
  for (int round = 0; round < 8; ++round) {
    for (int i = 0; i < 20000; ++i) {
      const Vec2 p = i % 2 ? Vec2(0.3f + 0.01f * u(rng), 0.6f + 0.01f * u(rng)) : Vec2(u(rng), u(rng));
      t.add(t.cell_of(p), 1.f);
    }
    t.sum_up();
    if (round < 7) t = t.refined(0.01);
  }
  ASSERT_GE(t.depth(), 6);
  ASSERT_LE(t.depth(), 10);
  const int n = 1024;
  for (int i = 0; i < 200000; ++i) {
    const int gx = int(rng() % n), gy = int(rng() % n);
    const Vec2 lo(float(gx) / n, float(gy) / n), size(1.f / n);
    const Vec2 centre = lo + 0.5f * size;
    const Vec2 inside = lo + Vec2(u(rng), u(rng)) * size * 0.999f;
    for (const Vec2& p : {lo, inside, Vec2(lo.x, centre.y), Vec2(centre.x, lo.y)}) {
      ASSERT_EQ(t.cell_of(p), t.cell_of(centre)) << p.x << " " << p.y;
      ASSERT_EQ(t.pdf(p), t.pdf(centre)) << p.x << " " << p.y;
    }
  }
  // The square's far edges and corner belong to the last cells.
  EXPECT_EQ(t.cell_of(Vec2(1.f, 1.f)), t.cell_of(Vec2(1.f - 0.5f / n, 1.f - 0.5f / n)));
  EXPECT_EQ(t.cell_of(Vec2(1.f, 0.f)), t.cell_of(Vec2(1.f - 0.5f / n, 0.5f / n)));
}
