#include "light/light_bvh.h"

#include <tbb/parallel_invoke.h>

#include <memory>

namespace lantern {

namespace {

// acos to within 7e-5 (Abramowitz & Stegun 4.4.45): a tenth of the cost of
// the library's, which the build spends most of its time in otherwise.
float acos_approx(float x) {
  const float ax = std::min(std::fabs(x), 1.f);
  const float r = std::sqrt(1.f - ax) * (1.5707288f + ax * (-0.2121144f + ax * (0.0742610f - 0.0187293f * ax)));
  return x >= 0.f ? r : kPi - r;
}
// Bounds on the approximation's error in sums of three angles, so that a
// union is never narrower than its parts.
constexpr float kAngleMargin = 3e-4f;

// The smallest cone holding two cones of directions (pbrt-v4's
// DirectionCone union, after Conty Estevez & Kulla 2018, Algorithm 1),
// widened by kAngleMargin: the importance's zeros rely on it holding every
// normal.
void union_cone(Vec3 wa, float cos_a, Vec3 wb, float cos_b, Vec3* w, float* cos_o) {
  const float cos_d = glm::dot(wa, wb);
  // A cone holding the other's axis, and at least as wide, holds it all.
  if (cos_a <= cos_b && cos_d >= 1.f) return *w = wa, void(*cos_o = cos_a);
  if (cos_b < cos_a && cos_d >= 1.f) return *w = wb, void(*cos_o = cos_b);
  if (cos_a <= -1.f) return *w = wa, void(*cos_o = -1.f);
  if (cos_b <= -1.f) return *w = wb, void(*cos_o = -1.f);
  const float ta = acos_approx(cos_a), tb = acos_approx(cos_b), td = acos_approx(cos_d);
  if (td + tb + kAngleMargin <= ta) return *w = wa, void(*cos_o = cos_a);
  if (td + ta + kAngleMargin <= tb) return *w = wb, void(*cos_o = cos_b);
  const float to = 0.5f * (ta + td + tb) + kAngleMargin;
  const Vec3 axis = glm::cross(wa, wb);
  if (to >= kPi || glm::dot(axis, axis) < 1e-12f) return *w = wa, void(*cos_o = -1.f);
  // Rotate wa towards wb by theta_o - theta_a (Rodrigues).
  const float tr = to - ta;
  const Vec3 k = glm::normalize(axis);
  *w = glm::normalize(wa * std::cos(tr) + glm::cross(k, wa) * std::sin(tr) + k * glm::dot(k, wa) * (1.f - std::cos(tr)));
  *cos_o = std::cos(to);
}

// The bucket of centroid c among n over [lo, lo + extent]: the fraction
// first, since n (c - lo) overflows where the extent nears the largest
// float (lights 6e37 apart), and never outside [0, n - 1] (NaN: 0).
int bucket_index(float c, float lo, float extent, int n) {
  const float t = float(n) * ((c - lo) / extent);
  return t >= 0.f ? int(std::min(t, float(n - 1))) : 0;
}

// Conty Estevez & Kulla's orientation measure M_Omega times the box's
// surface area, power and a penalty for thin boxes: the split cost.
float split_cost(const LightBounds& b, int axis) {
  if (!(b.phi > 0.f)) return 0.f;
  const float to = acos_approx(b.cos_theta_o);
  const float te = acos_approx(b.cos_theta_e);
  const float tw = std::min(to + te, kPi);
  const float sin_o = std::sin(to);
  const float m_omega = 2.f * kPi * (1.f - b.cos_theta_o) +
                        0.5f * kPi * (2.f * tw * sin_o - std::cos(to - 2.f * tw) - 2.f * to * sin_o + b.cos_theta_o);
  const Vec3 d = b.hi - b.lo;
  const float area = 2.f * (d.x * d.y + d.y * d.z + d.z * d.x);
  const float longest = std::max(d.x, std::max(d.y, d.z));
  const float kr = d[axis] > 0.f ? longest / d[axis] : 1.f;
  return b.phi * m_omega * kr * std::max(area, 1e-20f);
}

struct TempNode {
  LightBounds bounds;
  uint32_t light = 0;
  std::unique_ptr<TempNode> child[2];
};

struct Builder {
  struct Item {
    LightBounds bounds;
    uint32_t light;
  };
  std::vector<Item> items;

  // Forces an even split below this depth, so that no light's path from
  // the root exceeds 64 turns (its trail's bits).
  static constexpr int kMaxSahDepth = 32;

  std::unique_ptr<TempNode> build(size_t begin, size_t end, int depth) {
    auto node = std::make_unique<TempNode>();
    if (end - begin == 1) {
      node->bounds = items[begin].bounds;
      node->light = items[begin].light;
      return node;
    }
    LightBounds all, centroids;
    for (size_t i = begin; i < end; ++i) {
      all = union_of(all, items[i].bounds);
      const Vec3 c = items[i].bounds.centroid();
      centroids.lo = glm::min(centroids.lo, c);
      centroids.hi = glm::max(centroids.hi, c);
    }
    size_t mid = depth < kMaxSahDepth ? sah_split(begin, end, all, centroids) : begin;
    if (mid == begin || mid == end) {  // no useful split: halve by count along the widest extent
      const Vec3 d = centroids.hi - centroids.lo;
      const int axis = d.x >= d.y && d.x >= d.z ? 0 : d.y >= d.z ? 1 : 2;
      mid = begin + (end - begin) / 2;
      std::nth_element(items.begin() + long(begin), items.begin() + long(mid), items.begin() + long(end),
                       [axis](const Item& a, const Item& b) { return a.bounds.centroid()[axis] < b.bounds.centroid()[axis]; });
    }
    node->bounds = all;
    auto left = [&] { node->child[0] = build(begin, mid, depth + 1); };
    auto right = [&] { node->child[1] = build(mid, end, depth + 1); };
    if (end - begin > 4096)
      tbb::parallel_invoke(left, right);
    else
      left(), right();
    return node;
  }

  // pbrt-v4's choice: 12 buckets per axis by centroid, the split of least
  // summed cost. Returns the partition point, or begin when none helps.
  size_t sah_split(size_t begin, size_t end, const LightBounds& all, const LightBounds& centroids) {
    constexpr int kBuckets = 12;
    float best = kInfinity;
    int best_axis = -1, best_bucket = -1;
    for (int axis = 0; axis < 3; ++axis) {
      const float lo = centroids.lo[axis], extent = centroids.hi[axis] - centroids.lo[axis];
      if (!(extent > 0.f)) continue;
      LightBounds bucket[kBuckets];
      auto bucket_of = [&](const Item& it) { return bucket_index(it.bounds.centroid()[axis], lo, extent, kBuckets); };
      for (size_t i = begin; i < end; ++i) {
        const int k = bucket_of(items[i]);
        bucket[k] = union_of(bucket[k], items[i].bounds);
      }
      // Costs of every prefix and suffix of buckets, each union formed once.
      float below[kBuckets], above[kBuckets];
      LightBounds acc;
      for (int k = 0; k < kBuckets; ++k) below[k] = split_cost(acc = union_of(acc, bucket[k]), axis);
      acc = LightBounds{};
      for (int k = kBuckets - 1; k > 0; --k) above[k] = split_cost(acc = union_of(acc, bucket[k]), axis);
      for (int split = 0; split < kBuckets - 1; ++split) {
        const float cost = below[split] + above[split + 1];
        if (cost < best) best = cost, best_axis = axis, best_bucket = split;
      }
    }
    if (best_axis < 0) return begin;
    const float lo = centroids.lo[best_axis], extent = centroids.hi[best_axis] - centroids.lo[best_axis];
    auto it = std::partition(items.begin() + long(begin), items.begin() + long(end), [&](const Item& t) {
      return bucket_index(t.bounds.centroid()[best_axis], lo, extent, kBuckets) <= best_bucket;
    });
    (void)all;
    return size_t(it - items.begin());
  }
};

}  // namespace

LightBounds union_of(const LightBounds& a, const LightBounds& b) {
  if (!(a.phi > 0.f)) return b;
  if (!(b.phi > 0.f)) return a;
  LightBounds u;
  u.lo = glm::min(a.lo, b.lo);
  u.hi = glm::max(a.hi, b.hi);
  u.phi = a.phi + b.phi;
  union_cone(a.w, a.cos_theta_o, b.w, b.cos_theta_o, &u.w, &u.cos_theta_o);
  u.cos_theta_e = std::min(a.cos_theta_e, b.cos_theta_e);
  u.two_sided = a.two_sided || b.two_sided;
  return u;
}

LightBvh::LightBvh(std::vector<LightBounds> bounds, std::vector<uint32_t> lights, size_t light_count) {
  trail_.assign(light_count, 0);
  in_tree_.assign(light_count, 0);
  Builder b;
  for (size_t i = 0; i < bounds.size(); ++i)
    if (bounds[i].phi > 0.f) b.items.push_back({bounds[i], lights[i]});
  if (b.items.empty()) return;
  std::unique_ptr<TempNode> root = b.build(0, b.items.size(), 0);
  // Flatten depth first: an interior node's first child follows it.
  nodes_.reserve(2 * b.items.size() - 1);
  struct Frame {
    const TempNode* node;
    uint64_t trail;
    int depth;
    int64_t parent;  // the interior node whose second child this is, or -1
  };
  std::vector<Frame> stack = {{root.get(), 0, 0, -1}};
  while (!stack.empty()) {
    Frame f = stack.back();
    stack.pop_back();
    if (f.parent >= 0) nodes_[size_t(f.parent)].index = uint32_t(nodes_.size());
    LightBvhNode n;
    n.bounds = prepare(f.node->bounds);
    depth_ = std::max(depth_, f.depth);
    if (!f.node->child[0]) {
      n.leaf = true;
      n.index = f.node->light;
      trail_[n.index] = f.trail;
      in_tree_[n.index] = 1;
      nodes_.push_back(n);
      continue;
    }
    const int64_t self = int64_t(nodes_.size());
    nodes_.push_back(n);
    stack.push_back({f.node->child[1].get(), f.trail | (uint64_t(1) << f.depth), f.depth + 1, self});
    stack.push_back({f.node->child[0].get(), f.trail, f.depth + 1, -1});
  }
}

bool LightBvh::sample(const Vec3& p, const Vec3& n, float u, uint32_t* light, float* pmf, float* u_remapped) const {
  if (nodes_.empty()) return false;
  size_t i = 0;
  float prob = 1.f;
  // A lone light can still be unable to light p.
  if (nodes_[0].leaf && !(light_importance(nodes_[0].bounds, p, n) > 0.f)) return false;
  while (!nodes_[i].leaf) {
    const size_t c0 = i + 1, c1 = nodes_[i].index;
    const float i0 = light_importance(nodes_[c0].bounds, p, n), i1 = light_importance(nodes_[c1].bounds, p, n);
    if (!(i0 + i1 > 0.f)) return false;
    const float p0 = i0 / (i0 + i1);
    if (u < p0) {
      i = c0;
      u = std::min(u / p0, kOneMinusEpsilon);
      prob *= p0;
    } else {
      i = c1;
      u = std::min((u - p0) / (1.f - p0), kOneMinusEpsilon);
      prob *= 1.f - p0;
    }
  }
  *light = nodes_[i].index;
  *pmf = prob;
  if (u_remapped) *u_remapped = u;
  return prob > 0.f;
}

float LightBvh::pmf(const Vec3& p, const Vec3& n, uint32_t light) const {
  if (light >= in_tree_.size() || !in_tree_[light]) return 0.f;
  if (nodes_[0].leaf) return light_importance(nodes_[0].bounds, p, n) > 0.f ? 1.f : 0.f;
  uint64_t trail = trail_[light];
  size_t i = 0;
  float prob = 1.f;
  while (!nodes_[i].leaf) {
    const size_t c0 = i + 1, c1 = nodes_[i].index;
    const float i0 = light_importance(nodes_[c0].bounds, p, n), i1 = light_importance(nodes_[c1].bounds, p, n);
    if (!(i0 + i1 > 0.f)) return 0.f;
    const float p0 = i0 / (i0 + i1);
    if (trail & 1) {
      i = c1;
      prob *= 1.f - p0;
    } else {
      i = c0;
      prob *= p0;
    }
    trail >>= 1;
  }
  return prob;
}

size_t LightBvh::memory_bytes() const {
  return nodes_.capacity() * sizeof(LightBvhNode) + trail_.capacity() * sizeof(uint64_t) + in_tree_.capacity();
}

}  // namespace lantern
