// Guiding fields learnt in shares: the field's sums are fixed-point, so a
// field does not depend on the order its records came in, and processes
// that each learn from a share of them and add up their sums
// (GuidingField::learnt_sums, as MPI's ranks do) learn the field one
// process learns from all of them, bit for bit.
#include <gtest/gtest.h>

#include <cstring>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include "guiding/guide_record.h"
#include "integrator/guiding_field.h"
#include "math/equal_area.h"

using namespace lantern;

namespace {

// Records for every tree of a field: directions in each bin of the
// radiance field and of the importance field, and scattered radiance.
struct Records {
  std::vector<GuideRecord> eye, light;
};

Records make_records(GuidingField& f, uint32_t seed, int n) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(0.f, 1.f);
  const Vec3 lo(-1.f), hi(2.f);
  Records r;
  for (int i = 0; i < n; ++i) {
    const Vec3 p = lo + (hi - lo) * Vec3(u(rng), u(rng), u(rng));
    // (energies over many orders of magnitude: their double sums would
    // depend on the order)
    const float energy = std::exp(8.f * u(rng) - 4.f);
    if (i % 5 == 4) {
      r.eye.push_back({f.scatter_field().leaf_of(p), 0, energy, 0.f, 0.f, -1.f, kScatteredRecord});
      continue;
    }
    for (const SDTree* tree : {&f.tree(), &f.importance_tree()}) {
      GuideRecord g{};
      g.leaf = tree->leaf_of(p);
      g.bin = uint8_t(i % SDTree::kBins);
      g.cell =
          tree->leaf(g.leaf).learning[g.bin].cell_of(equal_area_square_to_sphere(Vec2(0.1f + 0.3f * u(rng), u(rng))));
      g.energy = energy;
      g.second = energy * energy, g.bsdf_pdf = 0.3f, g.guide_pdf = i % 3 == 0 ? -1.f : u(rng);
      g.inv_distance = i % 2 == 0 ? 0.f : 0.2f + u(rng);  // (a mixture's parallax; a quadtree ignores it)
      (tree == &f.tree() ? r.eye : r.light).push_back(g);
    }
  }
  return r;
}

std::string add(const std::string& a, const std::string& b) {
  EXPECT_EQ(a.size(), b.size());
  std::string out = a;
  add_saturating_sums(out, b);
  return out;
}

// The records of even and of odd index.
std::pair<Records, Records> every_other(const Records& all) {
  Records a, b;
  for (size_t i = 0; i < all.eye.size(); ++i) (i % 2 ? b : a).eye.push_back(all.eye[i]);
  for (size_t i = 0; i < all.light.size(); ++i) (i % 2 ? b : a).light.push_back(all.light[i]);
  return {a, b};
}

// Two processes that learn one field, each from every other record, as
// MPI's ranks do (their sums added at each iteration's end).
struct TwoRanks {
  GuidingField whole, first, second;
  TwoRanks() : whole(Vec3(-1.f), Vec3(2.f), 64, true, true), first(whole), second(whole) {}
  // Deposits an iteration's records, or its first `share` of them.
  Records deposit(uint32_t seed, double share = 1.0) {
    Records all = make_records(whole, seed, 40000);
    all.eye.resize(size_t(double(all.eye.size()) * share));
    all.light.resize(size_t(double(all.light.size()) * share));
    whole.deposit(all.eye, all.light);
    const auto [a, b] = every_other(all);
    first.deposit(a.eye, a.light);
    second.deposit(b.eye, b.light);
    return all;
  }
  void end_iteration() {
    const std::string total = add(first.learnt_sums(), second.learnt_sums());
    first.take_learnt_sums(total);
    second.take_learnt_sums(total);
    whole.end_iteration(), first.end_iteration(), second.end_iteration();
  }
};

}  // namespace

// Three iterations: one process deposits all records in reverse order;
// two others each deposit every other one, then both take the sum of
// their sums. All three save the same bytes after every iteration.
static void expect_shares_add_up(GuideDistributionKind kind) {
  const Vec3 lo(-1.f), hi(2.f);
  GuidingSettings settings;
  settings.distribution = kind;
  GuidingField whole(lo, hi, 64, true, true, settings), first(lo, hi, 64, true, true, settings),
      second(lo, hi, 64, true, true, settings);
  for (uint32_t iteration = 0; iteration < 3; ++iteration) {
    const Records all = make_records(whole, 7 + iteration, 40000);
    Records reversed{{all.eye.rbegin(), all.eye.rend()}, {all.light.rbegin(), all.light.rend()}};
    whole.deposit(reversed.eye, reversed.light);
    const auto [a, b] = every_other(all);
    first.deposit(a.eye, a.light);
    second.deposit(b.eye, b.light);
    const std::string total = add(first.learnt_sums(), second.learnt_sums());
    first.take_learnt_sums(total);
    second.take_learnt_sums(total);
    EXPECT_EQ(first.save(), whole.save()) << "iteration " << iteration << ", inside it";
    whole.end_iteration(), first.end_iteration(), second.end_iteration();
    const std::string bytes = whole.save();
    EXPECT_EQ(first.save(), bytes) << "iteration " << iteration;
    EXPECT_EQ(second.save(), bytes) << "iteration " << iteration;
  }
  EXPECT_GE(whole.tree().leaves().size(), 4u);  // (they split alike)
  EXPECT_TRUE(whole.scatter_field().trained());
  // Sums of another field's shape are refused.
  GuidingField other(lo, hi, 64, true, false, settings);
  EXPECT_THROW(other.take_learnt_sums(whole.learnt_sums()), std::runtime_error);
}

// Fields of quadtrees and of lobes alike.
TEST(GuidingSums, SharesAddUpToTheWholeInAnyOrder) {
  for (const GuideDistributionKind kind : {GuideDistributionKind::kQuadtree, GuideDistributionKind::kMixture}) {
    SCOPED_TRACE(kind == GuideDistributionKind::kMixture ? "lobes" : "quadtrees");
    expect_shares_add_up(kind);
  }
}

// MPI ranks' checkpoint pieces each hold the field the ranks shared and
// their own sums since: joined, they are the field of one process that
// rendered both ranks' units, whether both pieces are of one iteration
// (saved inside it) or one is of the iteration before (saved at its end,
// before the ranks shared their sums).
TEST(GuidingSums, CheckpointPiecesOfRanksJoinIntoTheWhole) {
  TwoRanks r;
  r.deposit(11);
  r.end_iteration();
  r.deposit(12, 0.5);  // inside iteration 1
  const GuidingField fresh(Vec3(-1.f), Vec3(2.f), 64, true, true);
  GuidingField joined = fresh;
  joined.restore_joined({r.first.save(), r.second.save()});
  EXPECT_EQ(joined.save(), r.whole.save()) << "both pieces inside iteration 1";

  // The end of iteration 1: the second rank saved its piece, then the
  // first rank had its piece of iteration 2 saved after the exchange.
  TwoRanks s;
  s.deposit(11);
  s.end_iteration();
  s.deposit(12);
  const std::string second_at_end = s.second.save();
  s.end_iteration();
  s.deposit(13, 0.5);  // (the second rank's records of it are in no piece: not in the whole)
  GuidingField whole = fresh;
  {
    TwoRanks t;  // the whole, without the second rank's records of iteration 2
    t.deposit(11);
    t.end_iteration();
    t.deposit(12);
    t.end_iteration();
    Records all = make_records(t.whole, 13, 40000);
    all.eye.resize(all.eye.size() / 2), all.light.resize(all.light.size() / 2);
    const Records mine = every_other(all).first;
    t.whole.deposit(mine.eye, mine.light);
    whole = t.whole;
  }
  joined = fresh;
  joined.restore_joined({second_at_end, s.first.save()});
  EXPECT_EQ(joined.save(), whole.save()) << "one piece at the end of iteration 1, one inside iteration 2";
  joined = fresh;
  joined.restore_joined({s.first.save(), second_at_end});
  EXPECT_EQ(joined.save(), whole.save()) << "in the other order";

  // Pieces two iterations apart, or of one iteration with different
  // fields, cannot be joined.
  TwoRanks u;
  u.deposit(11);
  const std::string early = u.first.save();
  u.end_iteration();
  u.deposit(12);
  u.end_iteration();
  joined = fresh;
  EXPECT_THROW(joined.restore_joined({early, u.first.save()}), std::runtime_error);
  TwoRanks v;
  v.deposit(21);
  v.end_iteration();
  EXPECT_THROW(joined.restore_joined({r.first.save(), v.first.save()}), std::runtime_error);
}
