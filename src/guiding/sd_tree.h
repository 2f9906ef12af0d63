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
// its sign, the normal turned towards the side the path arrived from), and
// a seventh for the vertices that scatter in a medium there. A
// cell of the paper's size often holds both sides of a wall, or a floor and
// the wall it meets; one distribution for all of them sends a path on the
// dark side of a wall towards the light on the bright side, below its own
// surface, where the BSDF is zero: on a scene of two rooms joined by a
// door ajar (scenes/door-ajar.pbrt) 27% of guided paths ended so.
//
// Each leaf and normal also chooses the BSDF's share α of the mixture it
// is sampled with (integrator/guided_scatter.h), where the paper fixes 0.5
// and Müller 2019 learns it by gradient descent. Here: each record of the
// iteration carries its estimate F = f |cos| L / p_mix and the two
// densities of its direction, and for every candidate α' the second moment
// the mixture with α' would give, E[(f |cos| L)^2 / p'], is estimated from
// the same samples by reweighting, (f |cos| L)^2 / (p_mix p'); the
// candidate with the least becomes α. Where the guide does not pay, α goes
// up to 0.95 and the path tracer is nearly the unguided one; where it
// does, down to 0.15.
//
// α per leaf cannot take away the look-ups' and records' cost, so the
// tree also judges, render-wide, whether its guide pays at all (judge):
// each record carries (beta L)^2, the square of what its path brought the
// image after the vertex, and the iteration sums it as drawn and as the
// BSDF alone would have drawn it (reweighted by p_mix / p_bsdf, as the
// candidates above). Where the guide left more than 0.9 of the BSDF's sum
// in the third iteration, or more than 0.7 from the fourth on, it stops:
// no leaf is guided again.
// Guides that pay at equal time left 0.04 to 0.41 (lobes on the spotlit
// room and the tiny-light box, 0.41 at 96 x 96) and 0.28 to 0.56 (light
// subpaths on the caustics and the pool); those that do not, 0.78 to 1.02
// (the door ajar, the lantern, the Cornell box, the lamp street, bdpt's
// eye subpaths; light subpaths 0.87 to 0.99).
// The estimate favours the guide (the Cornell box: 0.83, where its
// images' error per sample is 1.2 times the unguided one's) and a guided
// sample costs 1.1 to 1.7 times an unguided one (docs/guiding-stop.md).
#pragma once

#include <array>
#include <cmath>
#include <cstdint>
#include <type_traits>
#include <vector>

#include "guiding/guide_distribution.h"
#include "guiding/guide_record.h"
#include "guiding/spatial_nodes.h"
#include "math/common.h"
#include "math/fixed_sum.h"

namespace lantern {

struct GuidingSettings {
  double spatial_threshold = 12000.0;   // c
  double directional_threshold = 0.01;  // ρ
  // (The render's options choose it, lobes by default: new_guiding_field.)
  GuideDistributionKind distribution = GuideDistributionKind::kQuadtree;
  bool stop_where_unpaid = true;  // judge (false: guide to the end, --guide-stop never)
};

class SDTree {
 public:
  static constexpr uint32_t kNormalBins = 6;
  static constexpr uint32_t kMediumBin = kNormalBins;  // vertices in a medium
  static constexpr uint32_t kBins = kNormalBins + 1;
  // The bin of a (unit) normal: its largest component's axis and sign.
  static uint32_t normal_bin(const Vec3& n) {
    const Vec3 a = glm::abs(n);
    const uint32_t axis = a.x >= a.y && a.x >= a.z ? 0u : (a.y >= a.z ? 1u : 2u);
    return 2u * axis + (n[int(axis)] < 0.f ? 1u : 0u);
  }

  static constexpr std::array<float, 6> kAlphas = {0.15f, 0.3f, 0.5f, 0.7f, 0.85f, 0.95f};
  static constexpr float kFirstAlpha = 0.5f;         // until the records say otherwise (the paper's)
  static constexpr uint32_t kAlphaMinRecords = 256;  // guided records a choice needs
  // judge: the first iteration judged (0 first) and the share of the
  // BSDF's sum a guide must stay below there, then from kJudgedFully on.
  // The third iteration samples a field learnt from passes 1 and 2 alone,
  // too little to find a small light (on the tiny-light box the lobes'
  // records left 0.39 to 0.41 of the BSDF's sum there, the fourth's 0.15
  // to 0.24, the fifth's 0.14 to 0.16), so only a guide that left nearly
  // all of it stops then: on the shipped scenes guides that pay left at
  // most 0.82 in their third iteration, and every one that left more than
  // 0.9 there (0.93 to 1.28) stopped after its fourth under the rule that
  // starts there (docs/guiding-stop.md). From the fourth, the share must
  // stay below 0.7. Last, the guided records, with light, a verdict needs.
  static constexpr uint32_t kFirstJudged = 2;
  static constexpr double kPaysBelowFirst = 0.9;
  static constexpr uint32_t kJudgedFully = 3;
  static constexpr double kPaysBelow = 0.7;
  static double pays_below(uint32_t iteration) { return iteration < kJudgedFully ? kPaysBelowFirst : kPaysBelow; }
  static constexpr uint64_t kJudgeMinRecords = 1024;
  // A tree no larger than this many leaves, of a few KB each
  // (split_spatial_leaf).
  static constexpr size_t kMostLeaves = size_t(1) << 18;

  struct Leaf {
    std::array<GuideDistribution, kBins> sampled, learning;
    uint64_t records = 0;  // this iteration's
    Vec3 size{0.f};        // the extents of its box
    std::array<float, kBins> alpha;
    // This iteration's second moments per candidate, and the records they
    // came from.
    // (Fixed-point, as the directional trees' energies: DirectionalTree.)
    std::array<std::array<FixedSum, kAlphas.size()>, kBins> moment{};
    std::array<uint32_t, kBins> moment_records{};
    explicit Leaf(GuideDistributionKind kind = GuideDistributionKind::kQuadtree) {
      alpha.fill(kFirstAlpha);
      if (kind != GuideDistributionKind::kQuadtree) sampled.fill(GuideDistribution(kind)), learning = sampled;
    }
  };
  using Node = SpatialNode;

  SDTree(Vec3 lo, Vec3 hi, GuidingSettings settings = {});

  uint32_t leaf_of(const Vec3& p) const;
  const Leaf& leaf(uint32_t i) const { return leaves_[i]; }
  void add(const GuideRecord& r) {
    Leaf& l = leaves_[r.leaf];
    l.learning[r.bin].add(r.cell, r.energy, r.inv_distance);
    ++l.records;
    add_to_verdict(r);
    if (r.guide_pdf < 0.f || !std::isfinite(r.second)) return;
    ++l.moment_records[r.bin];
    for (size_t c = 0; c < kAlphas.size(); ++c) {
      const float p = kAlphas[c] * r.bsdf_pdf + (1.f - kAlphas[c]) * r.guide_pdf;
      if (p > 0.f) l.moment[r.bin][c].add_saturating(float(double(r.second) / double(p)));
    }
  }
  // Ends iteration k (0 first): what was learnt is sampled from now on.
  void update(uint32_t iteration);
  // Calls f(FixedSum&) on each of this iteration's sums, in a fixed order:
  // the learning trees' energies, the records (as counts), the moments and
  // their records. Trees whose fields are the same (processes that learnt
  // alike until this iteration) have the same sums in the same order, so
  // processes can add theirs up (GuidingField::learnt_sums).
  template <class F>
  void visit_learnt(F&& f) {
    auto count = [&f](auto& n) {
      FixedSum c = FixedSum::of_count(uint64_t(n));
      f(c);
      n = static_cast<std::remove_reference_t<decltype(n)>>(c.count());
    };
    for (Leaf& l : leaves_) {
      for (GuideDistribution& d : l.learning)
        for (FixedSum& e : d.energies()) f(e);
      count(l.records);
      for (auto& m : l.moment)
        for (FixedSum& x : m) f(x);
      for (uint32_t& n : l.moment_records) count(n);
    }
    f(image_drawn_), f(image_bsdf_);
    count(image_guided_);
  }

  // Whether any leaf has a distribution to sample.
  bool trained() const { return trained_; }
  // Whether judge stopped the guide, after which iteration (0 first), and
  // the share of the BSDF's sum the guide left in the last iteration
  // judged (from the third on, with enough records; measured under
  // --guide-stop never too; -1: none yet).
  bool stopped() const { return stopped_; }
  uint32_t stopped_after() const { return stopped_after_; }
  double image_share() const { return image_share_; }
  // The BSDF's share α where a leaf's bin has a distribution to sample,
  // else -1: what a vertex looks up, kept apart from the leaves (whose
  // trees' sums it would read) and together, 7 floats a leaf.
  float guide_share(uint32_t leaf, uint32_t normal_bin) const { return guide_share_[leaf * kBins + normal_bin]; }

  const std::vector<Leaf>& leaves() const { return leaves_; }
  size_t memory_bytes() const;

  // The tree as it is, for a checkpoint. read_state restores it bit for
  // bit into a tree made for the same bounds, and throws
  // std::runtime_error for one made for others or one that cannot be.
  void write_state(StateWriter& out) const;
  void read_state(StateReader& in);

 private:
  static void choose_alphas(Leaf& l);
  // A record's (beta L)^2 into judge's sums: as drawn, and reweighted to
  // the BSDF's density where it was guided. A guided direction the BSDF
  // cannot draw (density 0: the path tracer keeps those the guide draws
  // where f is not 0) has no such weight, and a term a float cannot hold
  // says nothing: both are left out. (Terms below 2^-41, (beta L) below
  // about 7e-7, lose low bits in the fixed-point sums: a scene that dim
  // would need its terms scaled.)
  void add_to_verdict(const GuideRecord& r) {
    if (!(r.image > 0.f) || !std::isfinite(r.image)) return;
    const bool guided = r.guide_pdf >= 0.f;
    const float bsdf = guided ? float(double(r.image) * r.drawn_pdf / r.bsdf_pdf) : r.image;
    if (!(r.bsdf_pdf > 0.f) || !FixedSum::addable(bsdf) || !FixedSum::addable(r.image)) return;
    image_drawn_.add_saturating(r.image);
    image_bsdf_.add_saturating(bsdf);
    image_guided_ += guided;
  }
  void judge(uint32_t iteration);
  void index_guide_shares();

  SpatialCube cube_;  // the cube the tree divides
  GuidingSettings settings_;
  std::vector<Node> nodes_;
  std::vector<Leaf> leaves_;
  std::vector<float> guide_share_;  // kBins per leaf (guide_share)
  bool trained_ = false;
  // judge's: this iteration's sums of the records' (beta L)^2, as drawn and
  // as the BSDF alone would have, and its guided records.
  FixedSum image_drawn_, image_bsdf_;
  uint64_t image_guided_ = 0;
  bool stopped_ = false;
  uint32_t stopped_after_ = 0;
  double image_share_ = -1.0;
};

}  // namespace lantern
