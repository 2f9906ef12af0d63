// A distribution over directions that learns where light comes from: a
// quadtree over the equal-area square of the sphere (math/equal_area.h),
// each node holding the energy of its four quadrants (Müller, Gross and
// Novák 2017, "Practical Path Guiding for Efficient Light-Transport
// Simulation", sec. 3.2). The square is mapped to the sphere with constant
// Jacobian 4π, so a quadrant's share of the energy over its share of the
// square is its density.
//
// One tree plays two roles across an iteration of learning: the previous
// iteration's tree, whose energies are fixed, is sampled; a tree refined
// from it, with zero energies, collects this iteration's estimates
// (cell_of, then add). The energies are fixed-point sums (math/fixed_sum.h):
// the tree learnt from a set of estimates does not depend on the order
// they were added in, so processes that each add a share of them and then
// add up their sums (energies) learn the tree one process learns.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "math/common.h"
#include "math/fixed_sum.h"
#include "math/state_io.h"

namespace lantern {

class DirectionalTree {
 public:
  static constexpr int kMaxDepth = 20;  // Müller et al. 2017, sec. 5

  DirectionalTree();  // a root with four leaf quadrants, no energy

  // The leaf quadrant (node * 4 + quadrant) that point p of the square
  // falls in.
  uint32_t cell_of(Vec2 p) const;
  // (Sums past 2^63 stay there: FixedSum::add_saturating.)
  void add(uint32_t cell, float energy) { energy_[cell].add_saturating(energy); }
  // Sums every inner quadrant's energy from its child, after the adds, and
  // readies the tree to be sampled.
  void sum_up();

  double total() const {
    FixedSum all = energy_[0];
    for (int q = 1; q < 4; ++q) all.add_saturating(energy_[size_t(q)]);
    return all.value();
  }
  // A point of the square drawn proportionally to the energy (total() > 0)
  // and its density over the square.
  Vec2 sample(Vec2 u, float* pdf) const;
  float pdf(Vec2 p) const;

  // The structure for the next iteration, with zero energies: a quadrant
  // holding more than `threshold` of this tree's energy (the paper's ρ) is
  // split, down to kMaxDepth, a leaf's energy assumed spread evenly over it.
  // Without energy the structure stays.
  DirectionalTree refined(double threshold) const;

  // The tree as it is, for a checkpoint (what read_state restores bit for
  // bit). read_state throws std::runtime_error for a tree that cannot be
  // (a node with no parent or two, a child before its parent or past the
  // end, deeper than kMaxDepth, energies negative or not finite, or
  // counts of nodes and sums that do not fit).
  void write_state(StateWriter& out) const;
  void read_state(StateReader& in);

  size_t node_count() const { return node_.size(); }
  int depth() const;
  size_t memory_bytes() const { return node_.capacity() * sizeof(Node) + energy_.capacity() * sizeof(FixedSum); }
  // The energies, 4 per node, for adding up what processes learnt.
  std::vector<FixedSum>& energies() { return energy_; }

 private:
  // What sampling and densities read, together in 32 bytes: the children
  // (0: a leaf quadrant) and each quadrant's share of the node's energy
  // (sum_up), in floats, without a division.
  struct Node {
    std::array<uint32_t, 4> child{0, 0, 0, 0};
    std::array<float, 4> probability{0.f, 0.f, 0.f, 0.f};
  };
  std::vector<Node> node_;      // node 0 is the root; children come after their parent
  std::vector<FixedSum> energy_;  // 4 per node
  void normalise();
};

// Solid-angle density of a direction from the square's density.
inline float sphere_pdf(float square_pdf) { return square_pdf * kInv4Pi; }

}  // namespace lantern
