// Guiding fields learnt in shares: the field's sums are fixed-point, so a
// field does not depend on the order its records came in, and processes
// that each learn from a share of them and add up their sums
// (GuidingField::learnt_sums, as MPI's ranks do) learn the field one
// process learns from all of them, bit for bit.
#include <gtest/gtest.h>

#include <cstring>
#include <random>
#include <string>
#include <vector>

#include "guiding/guide_record.h"
#include "integrator/guiding_field.h"

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
      g.cell = tree->leaf(g.leaf).learning[g.bin].cell_of(Vec2(0.1f + 0.3f * u(rng), u(rng)));
      g.energy = energy;
      g.second = energy * energy, g.bsdf_pdf = 0.3f, g.guide_pdf = i % 3 == 0 ? -1.f : u(rng);
      (tree == &f.tree() ? r.eye : r.light).push_back(g);
    }
  }
  return r;
}

std::string add(const std::string& a, const std::string& b) {
  EXPECT_EQ(a.size(), b.size());
  std::string out = a;
  for (size_t at = 0; at + 16 <= a.size(); at += 16) {
    FixedSum::Raw x, y;
    std::memcpy(&x, a.data() + at, 16);
    std::memcpy(&y, b.data() + at, 16);
    FixedSum sum = FixedSum::of_raw(x);
    sum.add_saturating(FixedSum::of_raw(y));
    x = sum.raw();
    std::memcpy(out.data() + at, &x, 16);
  }
  return out;
}

}  // namespace

// Three iterations: one process deposits all records in reverse order;
// two others each deposit every other one, then both take the sum of
// their sums. All three save the same bytes after every iteration.
TEST(GuidingSums, SharesAddUpToTheWholeInAnyOrder) {
  const Vec3 lo(-1.f), hi(2.f);
  GuidingField whole(lo, hi, 64, true, true), first(lo, hi, 64, true, true), second(lo, hi, 64, true, true);
  for (uint32_t iteration = 0; iteration < 3; ++iteration) {
    const Records all = make_records(whole, 7 + iteration, 40000);
    Records reversed{{all.eye.rbegin(), all.eye.rend()}, {all.light.rbegin(), all.light.rend()}};
    whole.deposit(reversed.eye, reversed.light);
    Records a, b;
    for (size_t i = 0; i < all.eye.size(); ++i) (i % 2 ? b : a).eye.push_back(all.eye[i]);
    for (size_t i = 0; i < all.light.size(); ++i) (i % 2 ? b : a).light.push_back(all.light[i]);
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
  GuidingField other(lo, hi, 64, true, false);
  EXPECT_THROW(other.take_learnt_sums(whole.learnt_sums()), std::runtime_error);
}
