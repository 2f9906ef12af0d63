#include "integrator/vertex_grid.h"

namespace lantern {

void VertexGrid::build(const std::vector<Vec3>& p, float r) {
  start_.clear();
  index_.clear();
  if (p.empty() || !(r > 0.f)) return;
  lo_ = Vec3(kInfinity);
  for (const Vec3& x : p) lo_ = glm::min(lo_, x);
  inv_cell_ = 1.f / (2.f * r);
  r2_ = r * r;
  uint32_t size = 1;
  while (size < p.size() && size < (1u << 24)) size *= 2;
  mask_ = size - 1;
  start_.assign(size_t(size) + 1, 0u);
  std::vector<uint32_t> h(p.size());
  for (size_t j = 0; j < p.size(); ++j) ++start_[(h[j] = cell_hash(p[j])) + 1];
  for (uint32_t c = 0; c < size; ++c) start_[c + 1] += start_[c];
  index_.resize(p.size());
  std::vector<uint32_t> next(start_.begin(), start_.end() - 1);
  for (size_t j = 0; j < p.size(); ++j) index_[next[h[j]]++] = uint32_t(j);
}

}  // namespace lantern
