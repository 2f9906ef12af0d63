// What guided distances in media learn (integrator/guided_distance.h): the
// radiance that vertices in a medium scattered back along their paths, per
// unit scattering coefficient (next-event estimation's share included),
// averaged over the leaves of a binary tree over the scene's bounds, split
// in the middle along x, y and z in turn.
//
// A tree of its own, not the directional field's (guiding/sd_tree.h):
// there a leaf holds seven directional trees and splits by all records,
// which surfaces dominate, so in a room of fog its leaves stay about a
// metre wide, and a beam a few decimetres across is averaged with the dark
// around it. Here a leaf holds one mean and splits by the records of medium
// vertices alone, which every path that scatters leaves: a leaf with more
// than kSplit * sqrt(2^k) records in iteration k is split in two (the
// halves starting from its mean, each assumed to hold half the records,
// and split again while that is more), as practical path guiding splits
// its spatial tree (Müller, Gross and Novák 2017, sec. 3.3).
//
// Records are added in wave order by the renderer's serial stage, so the
// field, like the directional one, depends on the seed and not on threads.
#pragma once

#include <algorithm>
#include <cstdint>
#include <vector>

#include "guiding/spatial_nodes.h"
#include "math/common.h"
#include "math/fixed_sum.h"
#include "math/state_io.h"

namespace lantern {

class ScatterField {
 public:
  static constexpr double kSplit = 1600.0;
  // A tree no larger than this many leaves (split_spatial_leaf).
  static constexpr size_t kMostLeaves = size_t(1) << 22;

  ScatterField(Vec3 lo, Vec3 hi);

  uint32_t leaf_of(const Vec3& p) const;
  // The extents of a leaf's box.
  Vec3 size(uint32_t leaf) const { return leaves_[leaf].size; }
  // The mean the last iteration learnt in a leaf (0: none yet).
  float level(uint32_t leaf) const { return leaves_[leaf].level; }
  size_t leaf_count() const { return leaves_.size(); }
  // Leaves that learnt a mean above zero.
  size_t lit_leaves() const {
    return size_t(std::count_if(leaves_.begin(), leaves_.end(), [](const Leaf& l) { return l.level > 0.f; }));
  }

  // (Sums in fixed point, as the directional trees': the field learnt from
  // a set of records does not depend on their order.)
  void add(uint32_t leaf, float value) {
    leaves_[leaf].sum.add_saturating(value);
    ++leaves_[leaf].records;
  }
  // Ends iteration k (0 first): each leaf's records' mean is what it
  // knows from now on (a leaf no record reached keeps what it knew), and
  // leaves with many records split.
  void update(uint32_t iteration);
  bool trained() const { return trained_; }
  // Calls f(FixedSum&) on each of this iteration's sums (each leaf's sum and
  // records, as a count), in a fixed order (SDTree::visit_learnt).
  template <class F>
  void visit_learnt(F&& f) {
    for (Leaf& l : leaves_) {
      f(l.sum);
      FixedSum c = FixedSum::of_count(l.records);
      f(c);
      l.records = c.count();
    }
  }

  // The leaves the segment o + t d, t in [t0, t1], crosses inside the
  // field's cube, in order along it: visit(t_enter, t_exit, leaf) for each
  // stretch of positive length.
  template <class Visit>
  void leaves_along(const Vec3& o, const Vec3& d, float t0, float t1, Visit&& visit) const;

  size_t memory_bytes() const {
    return nodes_.capacity() * sizeof(Node) + split_.capacity() * sizeof(float) + leaves_.capacity() * sizeof(Leaf);
  }
  // The field as it is, for a checkpoint; read_state restores it bit for
  // bit into a field made for the same bounds, and throws
  // std::runtime_error for one made for others or bytes that cannot be.
  void write_state(StateWriter& out) const;
  void read_state(StateReader& in);

 private:
  using Node = SpatialNode;
  struct Leaf {
    Vec3 size{0.f};
    float level = 0.f;
    FixedSum sum;
    uint64_t records = 0;  // this iteration's
  };
  // Each inner node's split: the middle of its box along its axis.
  void derive_splits();
  template <class Visit>
  void visit_node(uint32_t n, const Vec3& o, const Vec3& d, const Vec3& inv_d, float ta, float tb, Visit& visit) const;

  SpatialCube cube_;  // the cube the tree divides
  std::vector<Node> nodes_;
  std::vector<float> split_;  // each inner node's plane, in the cube's units (derive_splits)
  std::vector<Leaf> leaves_;
  bool trained_ = false;
};

template <class Visit>
void ScatterField::leaves_along(const Vec3& o, const Vec3& d, float t0, float t1, Visit&& visit) const {
  // In the cube's own units, [0, 1]^3: clip to it (slabs), then descend.
  const Vec3 q = (o - cube_.lo) / cube_.extent, dq = d / cube_.extent;
  float ta = t0, tb = t1;
  for (int a = 0; a < 3; ++a) {
    if (dq[a] == 0.f) {
      if (q[a] < 0.f || q[a] > 1.f) return;
      continue;
    }
    float near = -q[a] / dq[a], far = (1.f - q[a]) / dq[a];
    if (near > far) std::swap(near, far);
    ta = std::max(ta, near), tb = std::min(tb, far);
  }
  if (!(ta < tb)) return;
  visit_node(0, q, dq, 1.f / dq, ta, tb, visit);
}

template <class Visit>
void ScatterField::visit_node(uint32_t n, const Vec3& o, const Vec3& d, const Vec3& inv_d, float ta, float tb,
                              Visit& visit) const {
  for (;;) {
    const Node& node = nodes_[n];
    if (node.child[0] == 0) {
      visit(ta, tb, node.leaf);
      return;
    }
    const int a = node.axis;
    // (parallel to the plane: infinite or not a number, never inside)
    const float split = split_[n];
    const float t_mid = (split - o[a]) * inv_d[a];
    if (d[a] == 0.f || !(t_mid > ta && t_mid < tb)) {  // the plane is not crossed within the stretch
      // The side the whole stretch lies on: where the ray heads once past
      // the plane, where it comes from before it (leaf_of's on the plane).
      const bool upper = d[a] == 0.f ? o[a] >= split : (t_mid <= ta) == (d[a] > 0.f);
      n = node.child[upper ? 1 : 0];
      continue;
    }
    // It crosses: the side it comes from first.
    const uint32_t near = node.child[d[a] > 0.f ? 0 : 1], far = node.child[d[a] > 0.f ? 1 : 0];
    visit_node(near, o, d, inv_d, ta, t_mid, visit);
    n = far, ta = t_mid;
  }
}

}  // namespace lantern
