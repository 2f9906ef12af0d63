#include "guiding/directional_tree.h"

#include <algorithm>
#include <limits>

#include "math/binary_digits.h"

namespace lantern {

namespace {

// A node's quadrant, x + 2y, is the next binary digit of each coordinate
// of the square (math/binary_digits.h; kMaxDepth is below 32): read, and
// moved on by one.
uint32_t next_quadrant(uint32_t& x, uint32_t& y) {
  const uint32_t q = (x >> 31) | ((y >> 31) << 1);
  x <<= 1;
  y <<= 1;
  return q;
}

// Chooses between two options of probabilities a and b (a + b > 0) with u,
// rescaling u to reuse it; false for the first.
bool choose_second(float a, float b, float& u) {
  const float first = a / (a + b);
  if (u < first) {
    u = std::min(u / first, 0x1.fffffep-1f);
    return false;
  }
  u = std::min((u - first) / (1.f - first), 0x1.fffffep-1f);
  return true;
}

}  // namespace

DirectionalTree::DirectionalTree() : node_(1), energy_(4) {}

void DirectionalTree::normalise() {
  for (size_t n = 0; n < node_.size(); ++n) {
    const FixedSum* e = &energy_[4 * n];
    FixedSum all = e[0];
    for (uint32_t q = 1; q < 4; ++q) all.add_saturating(e[q]);
    const double sum = all.value();
    for (uint32_t q = 0; q < 4; ++q) node_[n].probability[q] = sum > 0.0 ? float(e[q].value() / sum) : 0.f;
  }
}

uint32_t DirectionalTree::cell_of(Vec2 p) const {
  uint32_t n = 0, x = binary_digits(p.x), y = binary_digits(p.y);
  for (;;) {
    const uint32_t q = next_quadrant(x, y);
    const uint32_t c = node_[n].child[q];
    if (c == 0) return 4 * n + q;
    n = c;
  }
}

void DirectionalTree::sum_up() {
  // Children follow their parents, so walking backwards meets every child
  // before its parent.
  for (size_t n = node_.size(); n-- > 0;)
    for (uint32_t q = 0; q < 4; ++q)
      if (const uint32_t c = node_[n].child[q]; c != 0) {
        FixedSum all = energy_[4 * c];
        for (uint32_t k = 1; k < 4; ++k) all.add_saturating(energy_[4 * c + k]);
        energy_[4 * n + q] = all;
      }
  normalise();
}

Vec2 DirectionalTree::sample(Vec2 u, float* pdf) const {
  uint32_t n = 0;
  Vec2 origin(0.f);
  float size = 1.f, density = 1.f;
  u = glm::clamp(u, 0.f, 0x1.fffffep-1f);
  for (;;) {
    const Node& node = node_[n];
    const std::array<float, 4>& pr = node.probability;
    // The column first (x: quadrants 0 and 2 against 1 and 3), then the row.
    const uint32_t x = choose_second(pr[0] + pr[2], pr[1] + pr[3], u.x) ? 1u : 0u;
    const uint32_t y = choose_second(pr[x], pr[x + 2], u.y) ? 1u : 0u;
    const uint32_t q = x + 2u * y;
    density *= 4.f * pr[q];
    size *= 0.5f;
    origin += size * Vec2(float(x), float(y));
    const uint32_t c = node.child[q];
    if (c == 0) {
      *pdf = density;
      // Inside the cell, also where rounding would put it on the next one.
      const Vec2 end = origin + Vec2(size);
      return glm::min(origin + size * u, Vec2(std::nextafter(end.x, 0.f), std::nextafter(end.y, 0.f)));
    }
    n = c;
  }
}

float DirectionalTree::pdf(Vec2 p) const {
  uint32_t n = 0, x = binary_digits(p.x), y = binary_digits(p.y);
  float density = 1.f;
  for (;;) {
    const Node& node = node_[n];
    const uint32_t q = next_quadrant(x, y);
    density *= 4.f * node.probability[q];
    const uint32_t c = node.child[q];
    if (c == 0 || density == 0.f) return density;
    n = c;
  }
}

DirectionalTree DirectionalTree::refined(double threshold) const {
  DirectionalTree out;
  const double all = total();
  if (!(all > 0.0)) {
    out.node_ = node_;
    out.energy_.assign(energy_.size(), FixedSum());
    out.normalise();
    return out;
  }
  // Walks the new tree as it is made: each entry is a new node, the old
  // node it copies (or none, inside an old leaf), its depth, and the
  // energies of its quadrants.
  struct Entry {
    uint32_t node, old;  // old 0 with `inside`: no old node
    bool inside;
    int depth;
    std::array<double, 4> energy;
  };
  std::vector<Entry> stack{
      {0, 0, false, 1, {energy_[0].value(), energy_[1].value(), energy_[2].value(), energy_[3].value()}}};
  while (!stack.empty()) {
    const Entry e = stack.back();
    stack.pop_back();
    for (uint32_t q = 0; q < 4; ++q) {
      if (e.depth >= kMaxDepth || !(e.energy[q] > threshold * all)) continue;
      const uint32_t c = uint32_t(out.node_.size());
      out.node_[e.node].child[q] = c;
      out.node_.emplace_back();
      out.energy_.insert(out.energy_.end(), 4, FixedSum());
      const uint32_t old = e.inside ? 0u : node_[e.old].child[q];
      Entry next{c, old, e.inside || old == 0, e.depth + 1, {}};
      for (uint32_t k = 0; k < 4; ++k) next.energy[k] = next.inside ? e.energy[q] * 0.25 : energy_[4 * old + k].value();
      stack.push_back(next);
    }
  }
  out.normalise();
  return out;
}

int DirectionalTree::depth() const {
  std::vector<int> d(node_.size(), 1);
  int deepest = 1;
  for (size_t n = 0; n < node_.size(); ++n)
    for (uint32_t c : node_[n].child)
      if (c != 0) {
        d[c] = d[n] + 1;
        deepest = std::max(deepest, d[c]);
      }
  return deepest;
}

void DirectionalTree::write_state(StateWriter& out) const {
  out.put_vector(node_);
  out.put_vector(energy_);
}

void DirectionalTree::read_state(StateReader& in) {
  constexpr uint64_t kMostNodes = uint64_t(1) << 28;
  std::vector<Node> node = in.get_vector<Node>(kMostNodes);
  std::vector<FixedSum> energy = in.get_vector<FixedSum>(4 * kMostNodes);
  if (node.empty() || energy.size() != 4 * node.size())
    throw std::runtime_error("a directional tree of " + std::to_string(node.size()) + " nodes and " +
                             std::to_string(energy.size()) + " sums");
  // A tree: every node but the root the child of exactly one node, after
  // it, no deeper than kMaxDepth (so every walk from the root ends soon);
  // energies finite and not negative, shares of them in [0, 1].
  std::vector<uint8_t> parents(node.size(), 0), depth(node.size(), 0);
  for (size_t n = 0; n < node.size(); ++n)
    for (uint32_t c : node[n].child) {
      if (c == 0) continue;
      if (c <= n || c >= node.size() || parents[c]++ > 0 || depth[n] >= kMaxDepth)
        throw std::runtime_error("a directional tree whose node " + std::to_string(n) + " has child " + std::to_string(c));
      depth[c] = uint8_t(depth[n] + 1);
    }
  for (size_t n = 1; n < node.size(); ++n)
    if (parents[n] != 1) throw std::runtime_error("a directional tree whose node " + std::to_string(n) + " has no parent");
  for (const FixedSum& e : energy)
    if (!e.sane_total()) throw std::runtime_error("a directional tree's energy is " + std::to_string(e.value()));
  for (const Node& n : node)
    for (float p : n.probability)
      if (!(p >= 0.f && p <= 1.f)) throw std::runtime_error("a directional tree's share is " + std::to_string(p));
  node_ = std::move(node);
  energy_ = std::move(energy);
}

}  // namespace lantern
