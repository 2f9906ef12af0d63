// Path guiding in the renderer (docs/guiding.md): the field paths learn
// and sample, and its schedule. Learning runs in iterations of doubling
// length (Müller et al. 2017, sec. 4): iteration k covers passes
// [2^k - 1, 2^(k+1) - 1), one sample per pixel each; at its end the
// renderer lets its waves drain and calls end_iteration, and the field
// learnt in it is sampled from the next pass on. Every sample, those of
// the first iterations too, goes into the image: each is an unbiased
// estimate (one-sample MIS with the BSDF: integrator/guided_scatter.h).
//
// Determinism: waves make their records in parallel and the renderer's
// serial merge stage adds them in wave order (deposit), so the field and
// the image depend on the seed alone, not on the thread count.
#pragma once

#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include "guiding/sd_tree.h"
#include "integrator/guided_scatter.h"

namespace lantern {

class GuidingField {
 public:
  // passes: the render's budget in passes; 0 for a time budget, where the
  // renderer predicts it after each iteration (expect_passes).
  GuidingField(Vec3 lo, Vec3 hi, uint64_t passes) : tree_(lo, hi), passes_(passes) {}

  const SDTree& tree() const { return tree_; }
  // Where a surface vertex at p with shading normal ns, reached from
  // direction wo (towards where the path came from), finds the field: its
  // leaf, the bin of the normal turned to the side the path came from, and
  // the distribution there.
  struct Site {
    uint32_t leaf = 0, normal_bin = 0;
    GuideAt guide;
  };
  Site site(const Vec3& p, const Vec3& ns, const Vec3& wo) const {
    Site s;
    s.leaf = tree_.leaf_of(p);
    s.normal_bin = SDTree::normal_bin(glm::dot(ns, wo) < 0.f ? -ns : ns);
    s.guide = at(s.leaf, s.normal_bin);
    return s;
  }
  // Where a vertex in a medium at p finds the field: its leaf's medium bin.
  Site medium_site(const Vec3& p) const {
    Site s;
    s.leaf = tree_.leaf_of(p);
    s.normal_bin = SDTree::kMediumBin;
    s.guide = at(s.leaf, s.normal_bin);
    return s;
  }
  // The distribution paths sample in a leaf for a normal's bin, if it has
  // one (none before the first iteration ends, or where no energy came).
  GuideAt at(uint32_t leaf, uint32_t normal_bin) const {
    if (!tree_.trained()) return {};
    const SDTree::Leaf& l = tree_.leaf(leaf);
    const DirectionalTree& d = l.sampled[normal_bin];
    return d.total() > 0.0 ? GuideAt{&d, l.alpha[normal_bin]} : GuideAt{};
  }
  // Whether the waves of the current iteration record: the field they
  // learn is sampled for at least as many passes as the iteration lasts.
  // (Once not, never again: the last field learnt serves to the end, and
  // recording costs nothing more.)
  bool learning() const { return !done_ && (passes_ == 0 || pays(passes_)); }
  // Under a time budget: the passes the render is expected to reach.
  void expect_passes(uint64_t passes) {
    if (!done_ && passes > 0 && !pays(passes)) done_ = true;
  }
  // The pass count at which the current iteration ends.
  uint64_t iteration_end() const { return (uint64_t(2) << iteration_) - 1; }
  uint64_t iteration_length() const { return uint64_t(1) << iteration_; }
  uint32_t iteration() const { return iteration_; }

  void deposit(const std::vector<GuideRecord>& records) {
    for (const GuideRecord& r : records) tree_.add(r);
  }
  void end_iteration() {
    tree_.update(iteration_);
    if (iteration_ < 62) ++iteration_;
  }

  // The field, its iteration and whether it still learns, as bytes for a
  // checkpoint; restore takes them back into a field made for the same
  // render, and throws std::runtime_error for bytes it cannot take.
  std::string save() const {
    StringWriter out;
    out.put(iteration_);
    out.put(uint8_t(done_));
    tree_.write_state(out);
    return std::move(out.bytes);
  }
  void restore(const std::string& bytes) {
    StringReader in(bytes);
    const uint32_t iteration = in.get<uint32_t>();
    const bool done = in.get<uint8_t>() != 0;
    if (iteration > 62) throw std::runtime_error("a guiding field in iteration " + std::to_string(iteration));
    tree_.read_state(in);
    if (in.left() != 0) throw std::runtime_error("the guiding field has trailing bytes");
    iteration_ = iteration;
    done_ = done;
  }

 private:
  bool pays(uint64_t passes) const { return iteration_end() + iteration_length() <= passes; }

  SDTree tree_;
  uint64_t passes_;
  uint32_t iteration_ = 0;
  bool done_ = false;
};

}  // namespace lantern
