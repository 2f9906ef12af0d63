// A bounding volume hierarchy over emitters with finite positions, each
// node bounding its emitters' positions, normals and power (LightBounds).
// Next-event estimation descends it from the shading point, choosing each
// child in proportion to its importance, so a light near the point is
// chosen far more often than its share of the scene's power (Conty Estevez
// & Kulla 2018; pbrt-v4's "bvh" light sampler). The probability of any
// light is recomputed by walking down the light's own path from the root.
#pragma once

#include <cstdint>
#include <vector>

#include "light/light_bounds.h"

namespace lantern {

struct LightBvhNode {
  PreparedLightBounds bounds;
  uint32_t index = 0;  // leaf: the light (index into LightPools::all); interior: the second child
  bool leaf = false;   // an interior node's first child is the next node
};

class LightBvh {
 public:
  LightBvh() = default;
  // `bounds[i]` belongs to light `lights[i]`; lights with zero power are
  // left out (they are never chosen).
  LightBvh(std::vector<LightBounds> bounds, std::vector<uint32_t> lights, size_t light_count);

  bool empty() const { return nodes_.empty(); }
  // Chooses a light for point p with normal n (zero: none); false when
  // none can light p. u is reused across levels; u_remapped (optional) is
  // what is left of it at the leaf, uniform in [0, 1) given the choice.
  bool sample(const Vec3& p, const Vec3& n, float u, uint32_t* light, float* pmf, float* u_remapped = nullptr) const;
  float pmf(const Vec3& p, const Vec3& n, uint32_t light) const;

  size_t node_count() const { return nodes_.size(); }
  size_t memory_bytes() const;
  int depth() const { return depth_; }

 private:
  struct BuildItem {
    LightBounds bounds;
    uint32_t light;
  };
  uint32_t build(std::vector<BuildItem>& items, size_t begin, size_t end, int depth, uint64_t trail);

  std::vector<LightBvhNode> nodes_;
  // Per light: the turns from the root to its leaf (bit k: second child at
  // depth k), and whether it is in the tree at all.
  std::vector<uint64_t> trail_;
  std::vector<uint8_t> in_tree_;
  int depth_ = 0;
};

LightBounds union_of(const LightBounds& a, const LightBounds& b);

}  // namespace lantern
