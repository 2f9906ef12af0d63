#include "guiding/spatial_nodes.h"

#include <stdexcept>

#include "math/binary_digits.h"

namespace lantern {

// The axes alternate x, y, z from the root (split_spatial_leaf; a read
// tree is checked for it), so each level reads the next binary digit of
// one coordinate: the half of the node's box p lies in. (A tree grown here
// is at most 21 levels deep along an axis: split_spatial_leaf. Past 32, in
// a tree read from bytes, the lower halves are taken.)
uint32_t spatial_leaf_of(const std::vector<SpatialNode>& nodes, const SpatialCube& cube, const Vec3& p) {
  Vec3 q = glm::clamp((p - cube.lo) / cube.extent, 0.f, 1.f);
  if (!(q.x == q.x) || !(q.y == q.y) || !(q.z == q.z)) q = Vec3(0.5f);  // a NaN position: any leaf will do
  uint32_t x = binary_digits(q.x), y = binary_digits(q.y), z = binary_digits(q.z);
  const SpatialNode* node = nodes.data();
  for (;;) {
    if (node->child[0] == 0) return node->leaf;
    node = &nodes[node->child[x >> 31]];
    x <<= 1;
    if (node->child[0] == 0) return node->leaf;
    node = &nodes[node->child[y >> 31]];
    y <<= 1;
    if (node->child[0] == 0) return node->leaf;
    node = &nodes[node->child[z >> 31]];
    z <<= 1;
  }
}

std::vector<Vec3> spatial_leaf_centres(const std::vector<SpatialNode>& nodes, const SpatialCube& cube,
                                       size_t leaf_count) {
  std::vector<Vec3> centre(leaf_count, cube.lo + Vec3(0.5f * cube.extent));
  struct Box {
    uint32_t node;
    Vec3 lo, size;
  };
  std::vector<Box> stack{{0, cube.lo, Vec3(cube.extent)}};
  while (!stack.empty()) {
    Box b = stack.back();
    stack.pop_back();
    const SpatialNode& n = nodes[b.node];
    if (n.child[0] == 0) {
      if (n.leaf < leaf_count) centre[n.leaf] = b.lo + 0.5f * b.size;
      continue;
    }
    b.size[n.axis] *= 0.5f;
    Vec3 upper = b.lo;
    upper[n.axis] += b.size[n.axis];
    stack.push_back({n.child[0], b.lo, b.size});
    stack.push_back({n.child[1], upper, b.size});
  }
  return centre;
}

void write_spatial_nodes(StateWriter& out, const std::vector<SpatialNode>& nodes) {
  out.put(uint64_t(nodes.size()));
  for (const SpatialNode& n : nodes) {
    out.write(n.child, sizeof n.child);
    out.put(n.leaf);
    out.put(n.axis);
  }
}

std::vector<SpatialNode> read_spatial_nodes(StateReader& in, uint64_t leaf_bytes, uint64_t* leaf_count,
                                            const std::string& what) {
  // Each node takes 13 bytes: counts beyond what is left are damage.
  const uint64_t node_count = in.get<uint64_t>();
  if (node_count == 0 || node_count > in.left() / 13)
    throw std::runtime_error(what + " of " + std::to_string(node_count) + " nodes");
  std::vector<SpatialNode> nodes(node_count);
  for (SpatialNode& n : nodes) {
    in.read(n.child, sizeof n.child);
    n.leaf = in.get<uint32_t>();
    n.axis = in.get<uint8_t>();
  }
  const uint64_t leaves = in.get<uint64_t>();
  if (leaves == 0 || leaves > in.left() / leaf_bytes)
    throw std::runtime_error(what + " of " + std::to_string(leaves) + " leaves");
  // Every node but the root the child of one node, after it, at most
  // kMaxDepth deep (every walk from the root ends soon); each leaf in the
  // list, once.
  constexpr int kMaxDepth = 192;  // (a float's extent halves 24 times per axis at most: 72 levels)
  std::vector<uint8_t> parents(nodes.size(), 0), depth(nodes.size(), 0), named(leaves, 0);
  for (size_t i = 0; i < nodes.size(); ++i) {
    const SpatialNode& n = nodes[i];
    const bool leaf = n.child[0] == 0 && n.child[1] == 0;
    const bool inner = n.child[0] > i && n.child[1] > i && n.child[0] < node_count && n.child[1] < node_count &&
                       n.child[0] != n.child[1] && depth[i] < kMaxDepth;
    // (the axes alternate from x at the root: spatial_leaf_of reads them so)
    if ((!leaf && !inner) || n.axis != depth[i] % 3 || (leaf && (n.leaf >= leaves || named[n.leaf]++ > 0)))
      throw std::runtime_error(what + " whose node " + std::to_string(i) + " cannot be");
    if (inner)
      for (uint32_t c : n.child) {
        if (parents[c]++ > 0) throw std::runtime_error(what + " whose node " + std::to_string(c) + " has two parents");
        depth[c] = uint8_t(depth[i] + 1);
      }
  }
  *leaf_count = leaves;
  return nodes;
}

}  // namespace lantern
