// A distribution over directions that learns where light comes from as a
// mixture of von Mises-Fisher lobes, fitted to the records by weighted
// expectation-maximisation (Herholz et al. 2016, "Product Importance
// Sampling for Light Transport Path Guiding", sec. 4; Ruppert, Herholz and
// Lensch 2020, "Robust Fitting of Parallax-Aware Mixtures for Path
// Guiding", sec. 4 and 5). Where a quadtree (guiding/directional_tree.h)
// spreads a handful of records over the cells they fell in, a lobe turns
// them into a mean direction and a concentration: a small bright patch,
// found by a few records an iteration, becomes one sharp lobe.
//
// Parallax (Ruppert et al. 2020, sec. 5): the lobes are defined as seen
// from a pivot, a point of the leaf, and each knows how far away, on
// average, what it points at lies. A record is turned into the direction
// from the pivot to the point its path went on from (the vertex's position
// plus its direction times the distance to the next vertex), and each lobe
// sums the inverse distances of its records. A vertex elsewhere in the
// leaf sees each lobe re-aimed at that point: the mean becomes
// normalize(μ - (x - pivot) / d). So a leaf two metres wide does not blur
// a patch five metres away over the angle its width subtends. A record
// whose ray escaped has inverse distance 0: it points at infinity, where
// parallax is none.
//
// One mixture plays the two roles of an iteration as the quadtree does:
// the previous iteration's, fixed, is sampled; a copy of its lobes
// (refined) collects this iteration's records as sufficient statistics,
// each record split among the lobes by their responsibilities under that
// copy (the E-step, Dempster et al. 1977), and sum_up makes the new lobes
// from them (the M-step). So each iteration takes one step of EM from the
// last iteration's fit, on records twice as many (online EM across
// iterations, as Ruppert et al.'s, without keeping records). The sums are
// fixed-point (math/fixed_sum.h), so the fit does not depend on the order
// records arrive in, and processes add theirs up as for the quadtree.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "math/common.h"
#include "math/fixed_sum.h"
#include "math/state_io.h"

namespace lantern {

class VmfMixture {
 public:
  static constexpr uint32_t kLobes = 16;
  static constexpr float kFirstKappa = 4.f;             // the first lobes': about a radian wide
  static constexpr float kMostKappa = 5000.f;           // about 0.8 degrees
  static constexpr float kPriorRecords = 2.f;           // shrinks κ fitted from few records' worth (sum_up)
  static constexpr float kResponsibilityFloor = 0.02f;  // of the weight every lobe keeps in the E-step
  // Lobes with less of the energy are dropped from the sampled mixture
  // (their weight 0, the others' renormalised: the density stays the one
  // sampled), so that look-ups skip them.
  static constexpr float kLeastWeight = 0.005f;

  VmfMixture();  // kLobes broad lobes spread over the sphere, no energy
  struct Unused {};
  explicit VmfMixture(Unused) {}  // no lobes: what a quadtree's distribution holds

  // A record's unit direction, packed into 32 bits (what GuideRecord
  // carries as its cell): the octahedral map's coordinates, 16 bits each
  // (Cigolle et al. 2014, "A Survey of Efficient Representations for
  // Independent Unit Vectors"), within 1e-4 radians.
  static uint32_t cell_of(const Vec3& w);
  static Vec3 cell_direction(uint32_t cell);
  // Splits a record's energy among the lobes (the E-step): its direction
  // as seen from the pivot, and the inverse of its distance from there.
  void add(uint32_t cell, float energy, float inv_distance);
  const Vec3& pivot() const { return pivot_; }
  // The same lobes seen from another pivot: each re-aimed at the point it
  // points at, and its distance from there.
  void move_pivot(const Vec3& p);
  // The lobes from the sums (the M-step); readies the mixture to be
  // sampled. Without energy the lobes stay.
  void sum_up();
  double total() const;

  // A unit direction drawn from the mixture as seen from point x
  // (total() > 0), and the mixture's solid-angle density there.
  Vec3 sample(Vec2 u, const Vec3& x, float* pdf) const;
  float sphere_pdf(const Vec3& w, const Vec3& x) const;

  // The mixture for the next iteration: these lobes, no energy.
  VmfMixture refined() const;

  void write_state(StateWriter& out) const;
  void read_state(StateReader& in);

  size_t lobe_count() const { return lobe_.size(); }
  size_t memory_bytes() const {
    return lobe_.capacity() * sizeof(Lobe) + sum_.capacity() * sizeof(FixedSum) + row_.capacity() * sizeof(float);
  }
  // The sums, kSums per lobe, for adding up what processes learnt.
  std::vector<FixedSum>& energies() { return sum_; }

  struct Lobe {
    Vec3 mean{0.f, 0.f, 1.f};
    float kappa = kFirstKappa;
    float weight = 0.f;    // in the mixture that is sampled
    float e_weight = 0.f;  // in the E-step: the weight with a floor, so that no lobe stops learning
    float norm = 0.f;      // κ / (2π (1 - e^{-2κ})): the density at the mean
    float cdf = 0.f;       // the weights summed up to this lobe's, inclusive
    float inv_distance = 0.f;  // of what it points at, from the pivot (0: at infinity)
  };

 private:
  // Per lobe: energy times responsibility; the same times each coordinate
  // of the direction plus 1 (sums of terms that are not negative); the
  // square of energy times responsibility (the records' effective number);
  // energy times responsibility times inverse distance.
  static constexpr uint32_t kSums = 6;
  Vec3 pivot_{0.f};
  std::vector<Lobe> lobe_;
  std::vector<FixedSum> sum_;
  // What look-ups read, a row of kLobes each. For the E-step, every
  // lobe's mean, κ and the logarithm of its floored weight times norm, so
  // that a lobe's term is one exponential, exp(κ (μ·ω - 1) + log c). For
  // sampling and densities, the lobes of weight above 0 alone, first
  // (active_ of them): their means, κ, log weight times norm, inverse
  // distance, weight and weights summed up to theirs.
  enum Row { kX, kY, kZ, kKappa, kLogE, kSX, kSY, kSZ, kSKappa, kSLogC, kSInvDistance, kSWeight, kSCdf, kRows };
  uint32_t active_ = 0;
  bool parallax_ = false;  // whether any lobe sampled has a finite distance
  // The sampled lobes' means as seen from x, into rows of kLobes.
  void means_from(const Vec3& x, float* mx, float* my, float* mz) const;
  std::vector<float> row_;
  const float* row(Row r) const { return row_.data() + size_t(r) * kLobes; }
  void set_norms();

 public:
  // The fewest bytes a mixture's state takes (for checks of counts read).
  static constexpr uint64_t kStateBytes =
      sizeof(Vec3) + 8 + kLobes * sizeof(Lobe) + 8 + kLobes * kSums * sizeof(FixedSum);
};

}  // namespace lantern
