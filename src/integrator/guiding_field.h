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

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <stdexcept>
#include <string>
#include <vector>

#include "guiding/scatter_field.h"
#include "guiding/sd_tree.h"
#include "integrator/guided_scatter.h"
#include "lantern/render.h"

namespace lantern {

class GuidingField {
 public:
  // passes: the render's budget in passes; 0 for a time budget, where the
  // renderer predicts it after each iteration (expect_passes).
  // eye_subpaths: path and the eye subpaths of bdpt and vcm learn and
  // sample the radiance field; light_subpaths: the light subpaths of bdpt and vcm the
  // importance field.
  GuidingField(Vec3 lo, Vec3 hi, uint64_t passes, bool eye_subpaths = true, bool light_subpaths = false,
               GuidingSettings settings = {})
      : tree_(lo, hi, settings),
        importance_(lo, hi, settings),
        scattered_(lo, hi),
        passes_(passes),
        eye_subpaths_(eye_subpaths),
        light_subpaths_(light_subpaths) {}

  const SDTree& tree() const { return tree_; }
  // The importance field the light subpaths learn and sample (where
  // what leaves a surface reaches the image: docs/guiding.md), if they are
  // guided.
  // (Until the field's guide stops where it does not pay: SDTree::judge.)
  bool guides_light_subpaths() const { return light_subpaths_ && !importance_.stopped(); }
  bool guides_eye_subpaths() const { return eye_subpaths_ && !tree_.stopped(); }
  const SDTree& importance_tree() const { return importance_; }
  // What guides where the path tracer's rays scatter in homogeneous media
  // (integrator/guided_distance.h), once it has learnt; else null.
  const ScatterField* distance_field() const { return scattered_.trained() ? &scattered_ : nullptr; }
  const ScatterField& scatter_field() const { return scattered_; }
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
    s.guide = at(tree_, s.leaf, s.normal_bin, p);
    return s;
  }
  // Where a vertex in a medium at p finds the field: its leaf's medium bin.
  Site medium_site(const Vec3& p) const {
    Site s;
    s.leaf = tree_.leaf_of(p);
    s.normal_bin = SDTree::kMediumBin;
    s.guide = at(tree_, s.leaf, s.normal_bin, p);
    return s;
  }
  // Where a light subpath's surface vertex finds the importance field.
  Site importance_site(const Vec3& p, const Vec3& ns, const Vec3& wo) const {
    Site s;
    s.leaf = importance_.leaf_of(p);
    s.normal_bin = SDTree::normal_bin(glm::dot(ns, wo) < 0.f ? -ns : ns);
    s.guide = at(importance_, s.leaf, s.normal_bin, p);
    return s;
  }
  // The distribution paths sample in a leaf for a normal's bin, if it has
  // one (none before the first iteration ends, or where no energy came).
  GuideAt at(uint32_t leaf, uint32_t normal_bin, const Vec3& p) const { return at(tree_, leaf, normal_bin, p); }
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
  // The passes of the iterations before the current one: where learning
  // ended, once it has.
  uint64_t learnt_passes() const { return iteration_end() - iteration_length(); }
  uint32_t iteration() const { return iteration_; }

  void deposit(const std::vector<GuideRecord>& records, const std::vector<GuideRecord>& light_records = {}) {
    for (const GuideRecord& r : records) {
      if (r.bin == kScatteredRecord) {
        scattered_.add(r.leaf, r.energy);
      } else {
        tree_.add(r);
        ++records_, records_aimed_ += r.inv_distance > 0.f;
      }
    }
    for (const GuideRecord& r : light_records) importance_.add(r);
    light_records_ += light_records.size();
  }
  void end_iteration() {
    // (a tree whose guide stopped has no records to learn from: left as it was)
    if (eye_subpaths_ && !tree_.stopped()) tree_.update(iteration_);
    if (eye_subpaths_) scattered_.update(iteration_);
    if (light_subpaths_ && !importance_.stopped()) importance_.update(iteration_);
    if (iteration_ < 62) ++iteration_;
    // Nothing left to learn once every guide stopped and no distances are
    // guided: no more records, nor iterations' ends.
    if (!guides_eye_subpaths() && !guides_light_subpaths() && !scattered_.trained()) done_ = true;
  }

  // --stats: the fields in use (a tree the render does not sample, the
  // radiance field under --guide-light alone, is not counted).
  void report(RenderStats& stats) const {
    stats.guiding_iterations = iteration_;
    stats.guiding_records = records_, stats.guiding_records_aimed = records_aimed_;
    stats.guiding_light_records = light_records_;
    if (eye_subpaths_) {
      stats.guiding_stopped_after = tree_.stopped() ? int32_t(tree_.stopped_after()) : -1;
      stats.guiding_share = tree_.image_share();
    }
    if (light_subpaths_) {
      stats.guiding_light_stopped_after = importance_.stopped() ? int32_t(importance_.stopped_after()) : -1;
      stats.guiding_light_share = importance_.image_share();
    }
    auto count = [&](const SDTree& tree) {
      for (const SDTree::Leaf& l : tree.leaves()) {
        for (uint32_t b = 0; b < SDTree::kBins; ++b)
          stats.guiding_nodes += l.sampled[b].node_count() + l.learning[b].node_count();
        if (l.sampled[SDTree::kMediumBin].total() > 0.0) ++stats.guiding_medium_leaves;
      }
      stats.guiding_bytes += tree.memory_bytes();
      return tree.leaves().size();
    };
    if (eye_subpaths_) stats.guiding_leaves = count(tree_);
    if (light_subpaths_) stats.guiding_light_leaves = count(importance_);
    if (scattered_.trained()) {
      stats.guiding_distance_leaves = scattered_.leaf_count();
      stats.guiding_distance_lit_leaves = scattered_.lit_leaves();
      stats.guiding_bytes += scattered_.memory_bytes();
    }
  }

  // What this iteration learnt so far, as its sums: 16-byte integers
  // (FixedSum::raw) that add up elementwise (FixedSum::add_saturating) across
  // processes that learnt alike until this iteration and each rendered a
  // share of it (MPI's ranks: RenderHooks::share_learnt). The totals, put
  // back with take_learnt_sums, are the sums one process that rendered
  // every share would have, bit for bit.
  std::string learnt_sums() {
    std::string bytes;
    visit_learnt([&bytes](FixedSum& s) {
      const FixedSum::Raw r = s.raw();
      bytes.append(reinterpret_cast<const char*>(&r), sizeof r);
    });
    return bytes;
  }
  void take_learnt_sums(const std::string& bytes) {
    size_t at = 0;
    visit_learnt([&](FixedSum&) { at += sizeof(FixedSum::Raw); });
    if (at != bytes.size())
      throw std::runtime_error("another process's guiding field has " + std::to_string(bytes.size()) +
                               " bytes of sums, this one " + std::to_string(at));
    at = 0;
    visit_learnt([&](FixedSum& s) {
      FixedSum::Raw r;
      std::memcpy(&r, bytes.data() + at, sizeof r);
      at += sizeof r;
      s = FixedSum::of_raw(r);
    });
  }

  // Forgets what this iteration learnt so far (a process that joins a
  // resumed render whose sums another process holds).
  void clear_learnt_sums() {
    visit_learnt([](FixedSum& s) { s = FixedSum(); });
  }

  // The field of a render whose processes each saved their own piece (MPI
  // ranks' checkpoint pieces, each save()d by its rank), restored
  // as one process that rendered every piece's units would hold it. Every
  // piece holds the field the processes shared at the start of its
  // iteration and its own sums since. A process saves its piece at the
  // end of every iteration before it shares its sums (run_passes.h), so no
  // process starts iteration k + 1 before every piece is of iteration k at
  // least: pieces are of the newest iteration, or of the one before saved
  // at its end, whose sums the newer pieces' field holds. So the newest
  // pieces' shared field and their sums added up are the whole.
  void restore_joined(const std::vector<std::string>& pieces) {
    if (pieces.size() == 1) return restore(pieces[0]);
    const GuidingField empty = *this;
    std::vector<uint32_t> iterations;
    uint32_t newest = 0;
    for (const std::string& piece : pieces) {
      StringReader in(piece);
      iterations.push_back(in.get<uint32_t>());
      newest = std::max(newest, iterations.back());
    }
    std::string total, shared;
    const std::string* first = nullptr;
    for (size_t i = 0; i < pieces.size(); ++i) {
      if (iterations[i] + 1 < newest)
        throw std::runtime_error("its pieces were saved in iterations " + std::to_string(iterations[i]) + " and " +
                                 std::to_string(newest) + " of the guiding field, more than one apart");
      if (iterations[i] != newest) continue;
      GuidingField f = empty;
      f.restore(pieces[i]);
      std::string sums = f.learnt_sums();
      f.clear_learnt_sums();
      std::string start = f.save();
      if (!first) {
        first = &pieces[i], total = std::move(sums), shared = std::move(start);
      } else {
        if (start != shared)
          throw std::runtime_error("two of its pieces hold different guiding fields of iteration " +
                                   std::to_string(newest));
        add_saturating_sums(total, sums);
      }
    }
    restore(*first);
    take_learnt_sums(total);
  }

  // The field, its iteration and whether it still learns, as bytes for a
  // checkpoint; restore takes them back into a field made for the same
  // render, and throws std::runtime_error for bytes it cannot take.
  std::string save() const {
    StringWriter out;
    out.put(iteration_);
    out.put(uint8_t(done_));
    tree_.write_state(out);
    out.put(uint8_t(eye_subpaths_));
    out.put(uint8_t(light_subpaths_));
    if (light_subpaths_) importance_.write_state(out);
    scattered_.write_state(out);
    return std::move(out.bytes);
  }
  void restore(const std::string& bytes) {
    StringReader in(bytes);
    const uint32_t iteration = in.get<uint32_t>();
    const bool done = in.get<uint8_t>() != 0;
    if (iteration > 62) throw std::runtime_error("a guiding field in iteration " + std::to_string(iteration));
    tree_.read_state(in);
    if (bool(in.get<uint8_t>()) != eye_subpaths_)
      throw std::runtime_error(eye_subpaths_ ? "its eye subpaths were not guided (--guide)" : "its eye subpaths were guided (--guide)");
    if (bool(in.get<uint8_t>()) != light_subpaths_)
      throw std::runtime_error(light_subpaths_ ? "its light subpaths were not guided (--guide-light)"
                                               : "its light subpaths were guided (--guide-light)");
    if (light_subpaths_) importance_.read_state(in);
    scattered_.read_state(in);
    if (in.left() != 0) throw std::runtime_error("the guiding field has trailing bytes");
    iteration_ = iteration;
    done_ = done;
  }

 private:
  template <class F>
  void visit_learnt(F&& f) {
    if (eye_subpaths_) tree_.visit_learnt(f);
    if (light_subpaths_) importance_.visit_learnt(f);
    scattered_.visit_learnt(f);
  }
  bool pays(uint64_t passes) const { return iteration_end() + iteration_length() <= passes; }
  // The distribution a tree's leaf holds for a normal's bin, if any (none
  // before the first iteration ends, or where no energy came).
  static GuideAt at(const SDTree& tree, uint32_t leaf, uint32_t normal_bin, const Vec3& p) {
    const float alpha = tree.guide_share(leaf, normal_bin);
    return alpha >= 0.f ? GuideAt{&tree.leaf(leaf).sampled[normal_bin], alpha, p} : GuideAt{};
  }

  SDTree tree_, importance_;
  ScatterField scattered_;  // guided distances: the path tracer's medium vertices learn it
  uint64_t passes_;
  bool eye_subpaths_, light_subpaths_;
  uint32_t iteration_ = 0;
  bool done_ = false;
  // (this process's records since it started, for --stats)
  uint64_t records_ = 0, records_aimed_ = 0, light_records_ = 0;
};

}  // namespace lantern
