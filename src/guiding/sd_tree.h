// The spatio-directional tree of practical path guiding (Müller, Gross and
// Novák 2017, sec. 3): a binary tree over the scene's bounds, split in the
// middle along x, y and z in turn, whose leaves each hold a directional
// distribution of incident radiance (guiding/directional_tree.h) in two
// versions: the one learnt in the last iteration, which paths sample, and
// the one being learnt, refined from it, which their records fill.
//
// Between iterations (update): the records' energies are summed; a leaf
// that received more than c * sqrt(2^k) records in iteration k is split
// (sec. 3.3, c = 12000), its children starting from copies of its
// distribution; then every leaf's learnt distribution becomes the one
// sampled, and a refined copy without energy the one filled next (sec. 3.2,
// ρ = 0.01).
//
// Unlike the paper's tree, a leaf keeps one directional distribution per
// orientation of the surface (six bins: the normal's largest component and
// its sign, the normal turned towards the side the path arrived from). A
// cell of the paper's size often holds both sides of a wall, or a floor and
// the wall it meets; one distribution for all of them sends a path on the
// dark side of a wall towards the light on the bright side, below its own
// surface, where the BSDF is zero: on a scene of two rooms joined by a
// door ajar (scenes/door-ajar.pbrt) 27% of guided paths ended so.
#pragma once

#include <array>

#include <cstdint>
#include <vector>

#include "guiding/directional_tree.h"
#include "guiding/guide_record.h"
#include "math/common.h"

namespace lantern {

struct GuidingSettings {
  double spatial_threshold = 12000.0;    // c
  double directional_threshold = 0.01;   // ρ
};

class SDTree {
 public:
  static constexpr uint32_t kNormalBins = 6;
  // The bin of a (unit) normal: its largest component's axis and sign.
  static uint32_t normal_bin(const Vec3& n) {
    const Vec3 a = glm::abs(n);
    const uint32_t axis = a.x >= a.y && a.x >= a.z ? 0u : (a.y >= a.z ? 1u : 2u);
    return 2u * axis + (n[int(axis)] < 0.f ? 1u : 0u);
  }

  struct Leaf {
    std::array<DirectionalTree, kNormalBins> sampled, learning;
    uint64_t records = 0;  // this iteration's
    Vec3 size{0.f};        // the extents of its box
  };
  struct Node {
    uint32_t child[2] = {0, 0};  // 0: a leaf
    uint32_t leaf = 0;           // a leaf's index in leaves()
    uint8_t axis = 0;
  };

  SDTree(Vec3 lo, Vec3 hi, GuidingSettings settings = {});

  uint32_t leaf_of(const Vec3& p) const;
  const Leaf& leaf(uint32_t i) const { return leaves_[i]; }
  void add(const GuideRecord& r) {
    Leaf& l = leaves_[r.leaf];
    l.learning[r.bin].add(r.cell, double(r.energy));
    ++l.records;
  }
  // Ends iteration k (0 first): what was learnt is sampled from now on.
  void update(uint32_t iteration);

  // Whether any leaf has a distribution to sample.
  bool trained() const { return trained_; }

  const std::vector<Node>& nodes() const { return nodes_; }
  const std::vector<Leaf>& leaves() const { return leaves_; }
  Vec3 lo() const { return lo_; }
  float extent() const { return extent_; }
  size_t memory_bytes() const;

  // Rebuilt from a checkpoint's copy; false if the parts do not fit.
  bool assign(std::vector<Node> nodes, std::vector<Leaf> leaves, bool trained);

 private:
  void split(uint32_t node, uint32_t depth_axis, uint64_t limit);

  Vec3 lo_;
  float extent_;  // of the cube the tree divides
  GuidingSettings settings_;
  std::vector<Node> nodes_;
  std::vector<Leaf> leaves_;
  bool trained_ = false;
};

}  // namespace lantern
