// The directional distribution a guiding leaf holds for one normal's bin:
// a quadtree over the equal-area square (guiding/directional_tree.h, the
// SD-tree's, the default) or a mixture of von Mises-Fisher lobes
// (guiding/vmf_mixture.h; `--guide-distribution vmm`). One interface, so
// the spatial tree, the records, the α choice, checkpoints and MPI's sums
// are written once for both; a flag, not a virtual call, picks the kind
// at each look-up (every leaf of a render has the same kind, so the branch
// is always predicted).
#pragma once

#include <cstdint>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "guiding/directional_tree.h"
#include "guiding/vmf_mixture.h"
#include "math/equal_area.h"

namespace lantern {

enum class GuideDistributionKind : uint8_t { kQuadtree = 0, kMixture = 1 };

class GuideDistribution {
 public:
  GuideDistribution() = default;
  explicit GuideDistribution(GuideDistributionKind kind) : kind_(kind) {
    if (kind_ == GuideDistributionKind::kMixture) mixture_ = VmfMixture();
  }
  explicit GuideDistribution(DirectionalTree tree) : tree_(std::move(tree)) {}
  bool is_mixture() const { return kind_ == GuideDistributionKind::kMixture; }

  // The cell of a unit direction a record goes to (for a mixture, the
  // direction itself, packed).
  uint32_t cell_of(const Vec3& w) const {
    return is_mixture() ? VmfMixture::cell_of(w) : tree_.cell_of(equal_area_sphere_to_square(w));
  }
  void add(uint32_t cell, float energy, float inv_distance) {
    is_mixture() ? mixture_.add(cell, energy, inv_distance) : tree_.add(cell, energy);
  }
  // The point directions are seen from (a mixture's pivot), and moving it
  // (a quadtree has none: it sees every point of its leaf alike).
  Vec3 pivot() const { return is_mixture() ? mixture_.pivot() : Vec3(0.f); }
  void move_pivot(const Vec3& p) {
    if (is_mixture()) mixture_.move_pivot(p);
  }
  void sum_up() { is_mixture() ? mixture_.sum_up() : tree_.sum_up(); }
  double total() const { return is_mixture() ? mixture_.total() : tree_.total(); }
  // A unit direction drawn from the distribution as seen from point x
  // (total() > 0), and its solid-angle density.
  Vec3 sample_direction(Vec2 u, const Vec3& x, float* pdf) const {
    if (is_mixture()) return mixture_.sample(u, x, pdf);
    float square_pdf = 0.f;
    const Vec3 w = glm::normalize(equal_area_square_to_sphere(tree_.sample(u, &square_pdf)));
    *pdf = lantern::sphere_pdf(square_pdf);
    return w;
  }
  float sphere_pdf(const Vec3& w, const Vec3& x) const {
    return is_mixture() ? mixture_.sphere_pdf(w, x) : lantern::sphere_pdf(tree_.pdf(equal_area_sphere_to_square(w)));
  }
  GuideDistribution refined(double threshold) const {
    GuideDistribution out(*this, Empty{});
    if (is_mixture())
      out.mixture_ = mixture_.refined();
    else
      out.tree_ = tree_.refined(threshold);
    return out;
  }
  std::vector<FixedSum>& energies() { return is_mixture() ? mixture_.energies() : tree_.energies(); }
  // Quadtree nodes or lobes.
  size_t node_count() const { return is_mixture() ? mixture_.lobe_count() : tree_.node_count(); }
  size_t memory_bytes() const { return is_mixture() ? mixture_.memory_bytes() : tree_.memory_bytes(); }
  const DirectionalTree& tree() const { return tree_; }

  // The state of the kind this one is (a checkpoint's fingerprint says
  // which kind its field holds: render_checkpoints.cpp).
  void write_state(StateWriter& out) const { is_mixture() ? mixture_.write_state(out) : tree_.write_state(out); }
  void read_state(StateReader& in) { is_mixture() ? mixture_.read_state(in) : tree_.read_state(in); }

 private:
  struct Empty {};
  GuideDistribution(const GuideDistribution& like, Empty) : kind_(like.kind_) {}
  GuideDistributionKind kind_ = GuideDistributionKind::kQuadtree;
  DirectionalTree tree_;
  VmfMixture mixture_{VmfMixture::Unused{}};
};

}  // namespace lantern
