#include "guiding/scatter_field.h"

#include <cmath>
#include <stdexcept>
#include <string>

namespace lantern {

ScatterField::ScatterField(Vec3 lo, Vec3 hi) {
  cube_ = SpatialCube::around(lo, hi);
  nodes_.push_back(Node{});
  leaves_.push_back(Leaf{Vec3(cube_.extent)});
}

uint32_t ScatterField::leaf_of(const Vec3& p) const { return spatial_leaf_of(nodes_, cube_, p); }

void ScatterField::update(uint32_t iteration) {
  for (Leaf& l : leaves_) {
    const float mean = l.records > 0 ? float(l.sum.value() / double(l.records)) : -1.f;
    if (mean >= 0.f && std::isfinite(mean)) l.level = mean;
    trained_ = trained_ || l.level > 0.f;
  }
  const uint64_t limit = uint64_t(kSplit * std::sqrt(std::ldexp(1.0, int(std::min(iteration, 60u)))));
  const size_t count = nodes_.size();  // the nodes before this update
  for (uint32_t n = 0; n < count; ++n)
    if (nodes_[n].child[0] == 0) split_spatial_leaf(nodes_, leaves_, n, limit, cube_, kMostLeaves);
  derive_splits();
  for (Leaf& l : leaves_) l.sum = FixedSum(), l.records = 0;
}

void ScatterField::derive_splits() {
  split_.assign(nodes_.size(), 0.f);
  struct Box {
    uint32_t node;
    Vec3 lo, hi;
  };
  std::vector<Box> stack{{0, Vec3(0.f), Vec3(1.f)}};
  while (!stack.empty()) {
    const Box b = stack.back();
    stack.pop_back();
    const Node& node = nodes_[b.node];
    if (node.child[0] == 0) continue;
    const int a = node.axis;
    const float split = split_[b.node] = 0.5f * (b.lo[a] + b.hi[a]);  // (halves of halves: exact in a float)
    Box lower{node.child[0], b.lo, b.hi}, upper{node.child[1], b.lo, b.hi};
    lower.hi[a] = upper.lo[a] = split;
    stack.push_back(lower);
    stack.push_back(upper);
  }
}

void ScatterField::write_state(StateWriter& out) const {
  cube_.write(out);
  out.put(uint8_t(trained_));
  write_spatial_nodes(out, nodes_);
  out.put(uint64_t(leaves_.size()));
  for (const Leaf& l : leaves_) {
    out.put(l.size);
    out.put(l.level);
    out.put(l.sum);
    out.put(l.records);
  }
}

void ScatterField::read_state(StateReader& in) {
  cube_.check(in, "the scattered radiance field");
  const bool trained = in.get<uint8_t>() != 0;
  uint64_t leaf_count = 0;
  std::vector<Node> nodes = read_spatial_nodes(in, 40, &leaf_count, "a scattered radiance tree");
  std::vector<Leaf> leaves(leaf_count);
  for (Leaf& l : leaves) {
    l.size = in.get<Vec3>();
    l.level = in.get<float>();
    l.sum = in.get<FixedSum>();
    l.records = in.get<uint64_t>();
    const bool fine = l.size.x > 0.f && l.size.y > 0.f && l.size.z > 0.f &&
                      std::isfinite(l.size.x + l.size.y + l.size.z) && l.level >= 0.f && std::isfinite(l.level) &&
                      l.sum.sane_total() && l.records < (uint64_t(1) << 40);
    if (!fine) throw std::runtime_error("a scattered radiance leaf whose size, mean or records cannot be");
  }
  nodes_ = std::move(nodes);
  leaves_ = std::move(leaves);
  trained_ = trained;
  derive_splits();
}

}  // namespace lantern
