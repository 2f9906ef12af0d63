// The film's fixed-point sums and unit sets: exact conversion, sums that do
// not depend on the order of their terms, and the set algebra that parts
// and checkpoints rely on.
#include "math/fixed_sum.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "film/unit_set.h"

namespace lantern {
namespace {

TEST(FixedSum, ConvertsExactly) {
  const FixedSum::Raw one = FixedSum::Raw(1) << 64;
  EXPECT_TRUE(FixedSum::to_fixed(1.f) == one);
  EXPECT_TRUE(FixedSum::to_fixed(-0.5f) == -(one >> 1));
  EXPECT_TRUE(FixedSum::to_fixed(0x1p-41f) == (FixedSum::Raw(1) << 23));
  EXPECT_TRUE(FixedSum::to_fixed(0x1p-64f) == 1);
  EXPECT_TRUE(FixedSum::to_fixed(0x1p-70f) == 0);  // below the resolution
  EXPECT_TRUE(FixedSum::to_fixed(0.f) == 0);
  EXPECT_TRUE(FixedSum::to_fixed(-0.f) == 0);
  EXPECT_TRUE(FixedSum::to_fixed(3.0e18f) == FixedSum::Raw(3.0e18f) * one);
  EXPECT_FALSE(FixedSum::addable(5e18f));
  EXPECT_FALSE(FixedSum::addable(INFINITY));
  EXPECT_FALSE(FixedSum::addable(NAN));
  EXPECT_TRUE(FixedSum::addable(-4e18f));
  FixedSum s;
  s.add(1.25f);
  s.add(-3.5f);
  EXPECT_EQ(s.value(), -2.25);
}

// The same terms in any order give the same bits; a double sum does not
// (so the test can tell), and the fixed sum is the closer to the exact one.
TEST(FixedSum, OrderDoesNotMatter) {
  std::mt19937 rng(7);
  std::lognormal_distribution<float> size(0.f, 6.f);
  std::vector<float> terms(20000);
  for (float& t : terms) t = size(rng) * (rng() % 5 == 0 ? -1.f : 1.f);
  FixedSum first;
  for (float t : terms) first.add(t);
  bool double_differs = false;
  double first_double = 0.0;
  for (float t : terms) first_double += double(t);
  for (int round = 0; round < 5; ++round) {
    std::shuffle(terms.begin(), terms.end(), rng);
    FixedSum again;
    double d = 0.0;
    for (float t : terms) {
      again.add(t);
      d += double(t);
    }
    EXPECT_TRUE(again.raw() == first.raw());
    double_differs |= d != first_double;
  }
  EXPECT_TRUE(double_differs);
  long double exact = 0.0L;
  for (float t : terms) exact += (long double)t;
  EXPECT_LE(std::fabs((long double)first.value() - exact), std::fabs((long double)first_double - exact) + 1e-6L);
  // Split into two partial sums added later: still the same bits.
  FixedSum a, b;
  for (size_t i = 0; i < terms.size(); ++i) (i % 3 ? a : b).add(terms[i]);
  b.add(a);
  EXPECT_TRUE(b.raw() == first.raw());
}

TEST(UnitSet, InsertContainsUnionOverlap) {
  UnitSet s;
  for (uint64_t u : {0, 1, 2, 5, 6, 9}) s.insert(u);
  EXPECT_EQ(s.size(), 6u);
  EXPECT_EQ(s.intervals().size(), 3u);
  EXPECT_TRUE(s.contains(2));
  EXPECT_FALSE(s.contains(3));
  EXPECT_TRUE(s.contains(9));
  EXPECT_FALSE(s.contains(10));
  s.insert(4);  // out of order: merges with [5, 7)
  s.insert(3);  // joins [0, 3) and [4, 7)
  EXPECT_EQ(s.intervals(), (std::vector<UnitSet::Interval>{{0, 7}, {9, 10}}));
  s.insert(3);  // again: no change
  EXPECT_EQ(s.size(), 8u);
  const UnitSet t = UnitSet::of({{7, 9}, {12, 14}});
  EXPECT_FALSE(s.overlaps(t));
  EXPECT_TRUE(s.overlaps(UnitSet::of({{6, 8}})));
  s.add(t);
  EXPECT_EQ(s.intervals(), (std::vector<UnitSet::Interval>{{0, 10}, {12, 14}}));
  EXPECT_EQ(s.size(), 12u);
  EXPECT_FALSE(UnitSet::valid({{3, 3}}));
  EXPECT_FALSE(UnitSet::valid({{0, 4}, {4, 6}}));
  EXPECT_TRUE(UnitSet::valid({{0, 4}, {5, 6}}));
}

// Shares split the units exactly, count them right, and each covers every
// wave (every pixel) once there are as many passes as shares.
TEST(UnitSet, SharesPartitionTheUnits) {
  for (uint32_t n : {1u, 2u, 3u, 7u})
    for (uint64_t waves : {1u, 6u, 7u, 10u}) {
      const uint64_t passes = 9;
      uint64_t total = 0;
      for (uint32_t k = 0; k < n; ++k) {
        const UnitShare share{k, n};
        uint64_t counted = 0;
        std::vector<bool> covered(waves, false);
        for (uint64_t p = 0; p < passes; ++p)
          for (uint64_t w = 0; w < waves; ++w)
            if (share.holds(p, w)) {
              ++counted;
              covered[w] = true;
            }
        EXPECT_EQ(share.size_of(passes, waves), counted) << n << " " << waves;
        if (n <= passes && waves >= n) EXPECT_EQ(std::count(covered.begin(), covered.end(), true), int(waves));
        total += counted;
      }
      EXPECT_EQ(total, passes * waves);
    }
}

}  // namespace
}  // namespace lantern

// The guiding fields' sums: a saturating sum of positive terms is
// min(the true sum, 2^63) in any order, also across the saturation; terms
// that are not positive (NaN too) add nothing; counts come back.
TEST(FixedSum, SaturatingSumsAreTheSameInAnyOrder) {
  const std::vector<float> terms = {4e18f, 3e18f, 1.f, 2.5e18f, 0.25f, 1e30f, 7.f};
  FixedSum forward, backward;
  for (float t : terms) forward.add_saturating(t);
  for (auto it = terms.rbegin(); it != terms.rend(); ++it) backward.add_saturating(*it);
  EXPECT_EQ(forward.raw(), backward.raw());
  EXPECT_TRUE(forward.sane_total());
  EXPECT_NEAR(forward.value(), 0x1p63, 0x1p63 * 1e-12);  // saturated
  // Two partial sums, saturated or not, add up to the same.
  FixedSum a, b;
  for (size_t i = 0; i < terms.size(); ++i) (i % 2 ? b : a).add_saturating(terms[i]);
  a.add_saturating(b);
  EXPECT_EQ(a.raw(), forward.raw());
  // Below saturation, the exact sum.
  FixedSum small;
  for (float t : {1.5f, 0.25f, 3.f}) small.add_saturating(t);
  EXPECT_EQ(small.value(), 4.75);
  for (float t : {-1.f, 0.f, std::nanf(""), -std::numeric_limits<float>::infinity()}) small.add_saturating(t);
  EXPECT_EQ(small.value(), 4.75) << "terms that are not positive add nothing";
  EXPECT_EQ(FixedSum::of_count(123456789).count(), 123456789u);
  EXPECT_EQ(FixedSum::of_count(123456789).value(), 123456789.0);
  EXPECT_FALSE(FixedSum::of_raw(-1).sane_total());
}
