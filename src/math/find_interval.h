// Binary search over ascending tabulated nodes.
#pragma once

#include <algorithm>

namespace lantern {

// The largest i in [0, n - 2] with at(i) <= x, or 0 (x below the first
// node, or NaN): the interval [i, i + 1] that holds x, clamped to the
// table. at(i) must ascend.
template <class At>
int find_interval(int n, float x, At&& at) {
  int lo = 0, hi = n - 2;
  while (lo < hi) {
    const int mid = (lo + hi + 1) / 2;
    if (at(mid) <= x)
      lo = mid;
    else
      hi = mid - 1;
  }
  return std::max(lo, 0);
}

}  // namespace lantern
