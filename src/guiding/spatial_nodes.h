// The spatial binary trees of path guiding (guiding/sd_tree.h,
// guiding/scatter_field.h): a cube divided in the middle along x, y and z
// in turn (the root x, its children y, theirs z, ...). Nodes sit in a
// list, children after their parent; a leaf names its entry in the tree's
// own list of leaves, which holds what it learns.
#pragma once

#include <algorithm>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include "math/common.h"
#include "math/state_io.h"

namespace lantern {

// The cube a tree divides: a little larger than the scene's bounds, so
// that every split halves all three extents in turn and points on the
// bounds fall inside.
struct SpatialCube {
  Vec3 lo{0.f};
  float extent = 1.f;
  static SpatialCube around(const Vec3& lo, const Vec3& hi) {
    const Vec3 size = glm::max(hi - lo, Vec3(0.f));
    SpatialCube c;
    c.extent = std::max(max_component(size), 1e-3f) * 1.01f;
    c.lo = 0.5f * (lo + hi) - Vec3(0.5f * c.extent);
    return c;
  }
  void write(StateWriter& out) const {
    out.put(lo);
    out.put(extent);
  }
  // Throws std::runtime_error, saying `what` was learnt in other bounds,
  // for another cube's bytes.
  void check(StateReader& in, const std::string& what) const {
    const Vec3 l = in.get<Vec3>();
    const float e = in.get<float>();
    if (l != lo || e != extent) throw std::runtime_error(what + " was learnt in other bounds");
  }
};

struct SpatialNode {
  uint32_t child[2] = {0, 0};  // 0: a leaf
  uint32_t leaf = 0;           // a leaf's index in the tree's leaves
  uint8_t axis = 0;            // the axis its children split
};

// The leaf of the tree over `cube` that p falls in (a point
// on a split plane: the upper side's; outside the cube: the nearest leaf).
uint32_t spatial_leaf_of(const std::vector<SpatialNode>& nodes, const SpatialCube& cube, const Vec3& p);

// Splits the leaf of node n in the middle along its node's axis while it
// holds more than `limit` records (Müller, Gross and Novák 2017, sec. 3.3):
// its halves start as copies of it, each assumed to hold half its records,
// and are split in turn along the next axis. A tree stops growing at
// `most_leaves` leaves, and no leaf grows narrower than the cube's extent
// over 2^20 along an axis: a count of records, as a damaged checkpoint may
// hold, cannot split it into more than memory holds. Leaf has `records`
// and `size` (its box's extents).
template <class Leaf>
void split_spatial_leaf(std::vector<SpatialNode>& nodes, std::vector<Leaf>& leaves, uint32_t n, uint64_t limit,
                        const SpatialCube& cube, size_t most_leaves) {
  const uint32_t first = nodes[n].leaf;
  const uint8_t axis = nodes[n].axis;
  if (leaves[first].records <= limit || leaves.size() >= most_leaves ||
      leaves[first].size[axis] < cube.extent * 0x1p-20f)
    return;
  leaves[first].records /= 2;
  leaves[first].size[axis] *= 0.5f;
  const uint32_t second = uint32_t(leaves.size());
  leaves.push_back(leaves[first]);
  const uint32_t a = uint32_t(nodes.size());
  const uint8_t next_axis = uint8_t((axis + 1) % 3);
  nodes.push_back(SpatialNode{{0, 0}, first, next_axis});
  nodes.push_back(SpatialNode{{0, 0}, second, next_axis});
  nodes[n].child[0] = a;
  nodes[n].child[1] = a + 1;
  split_spatial_leaf(nodes, leaves, a, limit, cube, most_leaves);
  split_spatial_leaf(nodes, leaves, a + 1, limit, cube, most_leaves);
}

// The centre of each leaf's box, by leaf index.
std::vector<Vec3> spatial_leaf_centres(const std::vector<SpatialNode>& nodes, const SpatialCube& cube,
                                       size_t leaf_count);

void write_spatial_nodes(StateWriter& out, const std::vector<SpatialNode>& nodes);
// What write_spatial_nodes wrote, and the count of leaves after it. Throws
// std::runtime_error, naming `what`, for counts beyond what the bytes left
// hold (a leaf takes at least leaf_bytes) or a list that is not a tree: a
// node with two parents, a child before its parent, deeper than 192
// levels, axes that do not alternate x, y, z from the root, a leaf outside
// the leaves or named twice.
std::vector<SpatialNode> read_spatial_nodes(StateReader& in, uint64_t leaf_bytes, uint64_t* leaf_count,
                                            const std::string& what);

}  // namespace lantern
