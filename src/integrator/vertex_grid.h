// A hashed grid over the light vertices of a wave, for vertex merging
// (vcm): cells of twice the merging radius, so the vertices within the
// radius of a point lie in the 2 x 2 x 2 cells around it. Built once per
// wave by a counting sort on the cells' hashes; queries touch eight short
// runs of indices.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "math/common.h"

namespace lantern {

class VertexGrid {
 public:
  // Indexes points p[0 .. n) for queries of radius r.
  void build(const std::vector<Vec3>& p, float r);
  // Calls f(j) for every point j within the radius of x (|p[j] - x| <= r).
  template <class F>
  void query(const std::vector<Vec3>& p, const Vec3& x, F&& f) const {
    if (start_.empty()) return;
    const Vec3 g = (x - lo_) * inv_cell_ - 0.5f;  // the lower of the two cells per axis
    const int cx = cell_of(g.x), cy = cell_of(g.y), cz = cell_of(g.z);
    uint32_t seen[8];
    int visited = 0;
    for (int c = 0; c < 8; ++c) {
      const uint32_t h = hash(cx + (c & 1), cy + ((c >> 1) & 1), cz + (c >> 2));
      bool again = false;  // two cells may share a hash bucket
      for (int k = 0; k < visited; ++k) again |= seen[k] == h;
      if (again) continue;
      seen[visited++] = h;
      for (uint32_t k = start_[h]; k < start_[h + 1]; ++k) {
        const uint32_t j = index_[k];
        const Vec3 d = p[j] - x;
        if (glm::dot(d, d) <= r2_) f(j);
      }
    }
  }
  size_t memory_bytes() const { return (start_.capacity() + index_.capacity()) * sizeof(uint32_t); }

 private:
  uint32_t hash(int x, int y, int z) const {
    return (uint32_t(x) * 73856093u ^ uint32_t(y) * 19349663u ^ uint32_t(z) * 83492791u) & mask_;
  }
  // A cell coordinate, clamped so that a tiny radius (huge coordinates)
  // stays in range: clamped points share a cell, and the distance test
  // still decides.
  static int cell_of(float g) {
    if (!(g > -1073741824.f)) return -1073741824;  // NaN too
    if (!(g < 1073741824.f)) return 1073741824;
    return int(std::floor(g));
  }
  uint32_t cell_hash(const Vec3& p) const {
    const Vec3 g = (p - lo_) * inv_cell_;
    return hash(cell_of(g.x), cell_of(g.y), cell_of(g.z));
  }
  Vec3 lo_{0.f};
  float inv_cell_ = 1.f, r2_ = 0.f;
  uint32_t mask_ = 0;
  std::vector<uint32_t> start_, index_;
};

}  // namespace lantern
