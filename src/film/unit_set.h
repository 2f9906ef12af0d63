// Which work units a film holds. A render is a fixed sequence of units (one
// wave of one pass each), numbered pass by pass: unit = pass * waves + wave.
// A film's fixed-point sums depend only on the set of units merged into it,
// so the set is all a checkpoint, a --part file or an MPI rank needs to say
// what it has and what is missing.
#pragma once

#include <algorithm>
#include <cstdint>
#include <iterator>
#include <utility>
#include <vector>

namespace lantern {

class UnitSet {
 public:
  using Interval = std::pair<uint64_t, uint64_t>;  // [first, end)

  // O(1) when units come in increasing order, as a render merges them.
  void insert(uint64_t u) {
    if (!runs_.empty() && runs_.back().second == u) {
      ++runs_.back().second;
      ++size_;
      return;
    }
    if (runs_.empty() || runs_.back().second < u) {
      runs_.emplace_back(u, u + 1);
      ++size_;
      return;
    }
    if (contains(u)) return;
    add(UnitSet::of({{u, u + 1}}));
  }

  bool contains(uint64_t u) const {
    auto it = std::upper_bound(runs_.begin(), runs_.end(), u, [](uint64_t x, const Interval& r) { return x < r.first; });
    return it != runs_.begin() && u < std::prev(it)->second;
  }

  // Union; the caller checks overlaps() first where overlap is an error.
  void add(const UnitSet& other) {
    std::vector<Interval> all;
    all.reserve(runs_.size() + other.runs_.size());
    std::merge(runs_.begin(), runs_.end(), other.runs_.begin(), other.runs_.end(), std::back_inserter(all));
    runs_.clear();
    size_ = 0;
    for (const Interval& r : all) {
      if (!runs_.empty() && r.first <= runs_.back().second)
        runs_.back().second = std::max(runs_.back().second, r.second);
      else
        runs_.push_back(r);
    }
    for (const Interval& r : runs_) size_ += r.second - r.first;
  }

  bool overlaps(const UnitSet& other) const {
    size_t i = 0, j = 0;
    while (i < runs_.size() && j < other.runs_.size()) {
      if (runs_[i].second <= other.runs_[j].first) ++i;
      else if (other.runs_[j].second <= runs_[i].first) ++j;
      else return true;
    }
    return false;
  }

  uint64_t size() const { return size_; }
  bool empty() const { return size_ == 0; }
  const std::vector<Interval>& intervals() const { return runs_; }

  // From sorted, disjoint intervals (a file's); false if they are not.
  static bool valid(const std::vector<Interval>& runs) {
    for (size_t i = 0; i < runs.size(); ++i)
      if (runs[i].first >= runs[i].second || (i > 0 && runs[i].first <= runs[i - 1].second)) return false;
    return true;
  }
  static UnitSet of(std::vector<Interval> runs) {
    UnitSet s;
    s.runs_ = std::move(runs);
    for (const Interval& r : s.runs_) s.size_ += r.second - r.first;
    return s;
  }

  friend bool operator==(const UnitSet& a, const UnitSet& b) { return a.runs_ == b.runs_; }

 private:
  std::vector<Interval> runs_;
  uint64_t size_ = 0;
};

// The units of share k of n (--part k+1/n): unit (pass, wave) belongs to
// share (pass + wave) mod n. Each share takes every n-th wave of a pass,
// shifted by one wave each pass, so that over n passes or more every share
// covers every pixel, and a missing share thins the image evenly instead of
// leaving holes.
struct UnitShare {
  uint32_t index = 0, count = 1;
  bool holds(uint64_t pass, uint64_t wave) const { return (pass + wave) % count == index; }
  // How many of the units of `passes` passes of `waves` waves it holds.
  uint64_t size_of(uint64_t passes, uint64_t waves) const {
    uint64_t total = 0;
    for (uint64_t j = 0; j < count && j < passes; ++j) {  // passes with pass % count == j
      const uint64_t passes_j = passes / count + (j < passes % count ? 1 : 0);
      const uint64_t r = (index + count - j) % count;       // first wave of share in such a pass
      total += passes_j * (waves > r ? (waves - 1 - r) / count + 1 : 0);
    }
    return total;
  }
};

}  // namespace lantern
