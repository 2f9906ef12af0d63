#include "guiding/sd_tree.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace lantern {

SDTree::SDTree(Vec3 lo, Vec3 hi, GuidingSettings settings) : settings_(settings) {
  cube_ = SpatialCube::around(lo, hi);
  nodes_.push_back(Node{});
  leaves_.push_back(Leaf(settings_.distribution));
  leaves_[0].size = Vec3(cube_.extent);
  for (GuideDistribution& d : leaves_[0].learning) d.move_pivot(cube_.lo + Vec3(0.5f * cube_.extent));
  index_guide_shares();
}

void SDTree::index_guide_shares() {
  guide_share_.assign(leaves_.size() * kBins, -1.f);
  if (!trained_ || stopped_) return;
  for (size_t i = 0; i < leaves_.size(); ++i)
    for (uint32_t b = 0; b < kBins; ++b)
      if (leaves_[i].sampled[b].total() > 0.0) guide_share_[i * kBins + b] = leaves_[i].alpha[b];
}

uint32_t SDTree::leaf_of(const Vec3& p) const { return spatial_leaf_of(nodes_, cube_, p); }

void SDTree::choose_alphas(Leaf& l) {
  for (uint32_t b = 0; b < kBins; ++b) {
    if (l.moment_records[b] >= kAlphaMinRecords) {
      const auto& m = l.moment[b];
      size_t least = 0;
      for (size_t c = 1; c < m.size(); ++c)
        if (m[c].value() < m[least].value()) least = c;
      // (all alike, as moments too small for the sums are, say nothing: α stays)
      const bool alike = std::all_of(m.begin(), m.end(), [&](const FixedSum& x) { return x.raw() == m[0].raw(); });
      if (!alike) l.alpha[b] = kAlphas[least];
    }
    l.moment[b].fill(FixedSum());
    l.moment_records[b] = 0;
  }
}

// Whether the guide paid for itself in iteration `iteration` (sd_tree.h):
// where the records' (beta L)^2 as drawn is more than pays_below of the
// BSDF's own, it stops for the rest of the render.
void SDTree::judge(uint32_t iteration) {
  const double drawn = image_drawn_.value(), bsdf = image_bsdf_.value();
  if (iteration >= kFirstJudged && image_guided_ >= kJudgeMinRecords && bsdf > 0.0) {
    image_share_ = drawn / bsdf;
    if (settings_.stop_where_unpaid && !stopped_ && image_share_ > pays_below(iteration))
      stopped_ = true, stopped_after_ = iteration;
  }
  image_drawn_ = FixedSum(), image_bsdf_ = FixedSum();
  image_guided_ = 0;
}

void SDTree::update(uint32_t iteration) {
  judge(iteration);
  for (Leaf& l : leaves_) {
    for (GuideDistribution& d : l.learning) d.sum_up();
    choose_alphas(l);
  }
  const uint64_t limit =
      uint64_t(settings_.spatial_threshold * std::sqrt(std::ldexp(1.0, int(std::min(iteration, 60u)))));
  const size_t count = nodes_.size();  // the leaves before this update
  for (uint32_t n = 0; n < count; ++n)
    if (nodes_[n].child[0] == 0) split_spatial_leaf(nodes_, leaves_, n, limit, cube_, kMostLeaves);
  trained_ = false;
  // (a mixture learns next as seen from its leaf's centre: a child's
  // copy of its parent's lobes is re-aimed there)
  const std::vector<Vec3> centre = spatial_leaf_centres(nodes_, cube_, leaves_.size());
  for (size_t i = 0; i < leaves_.size(); ++i) {
    Leaf& l = leaves_[i];
    for (uint32_t b = 0; b < kBins; ++b) {
      l.sampled[b] = std::move(l.learning[b]);
      l.learning[b] = l.sampled[b].refined(settings_.directional_threshold);
      l.learning[b].move_pivot(centre[i]);
      trained_ = trained_ || l.sampled[b].total() > 0.0;
    }
    l.records = 0;
  }
  index_guide_shares();
}

size_t SDTree::memory_bytes() const {
  size_t b =
      nodes_.capacity() * sizeof(Node) + leaves_.capacity() * sizeof(Leaf) + guide_share_.capacity() * sizeof(float);
  for (const Leaf& l : leaves_)
    for (uint32_t k = 0; k < kBins; ++k) b += l.sampled[k].memory_bytes() + l.learning[k].memory_bytes();
  return b;
}

void SDTree::write_state(StateWriter& out) const {
  cube_.write(out);
  out.put(uint8_t(trained_));
  write_spatial_nodes(out, nodes_);
  out.put(uint64_t(leaves_.size()));
  for (const Leaf& l : leaves_) {
    for (uint32_t b = 0; b < kBins; ++b) {
      l.sampled[b].write_state(out);
      l.learning[b].write_state(out);
    }
    out.put(l.records);
    out.put(l.size);
    out.put(l.alpha);
    out.put(l.moment);
    out.put(l.moment_records);
  }
  out.put(image_drawn_), out.put(image_bsdf_);
  out.put(image_guided_);
  out.put(uint8_t(stopped_));
  out.put(stopped_after_);
  out.put(image_share_);
}

void SDTree::read_state(StateReader& in) {
  cube_.check(in, "the guiding field");
  const bool trained = in.get<uint8_t>() != 0;
  // A leaf takes at least 14 distributions, quadtrees of one node (112
  // bytes each) or mixtures (VmfMixture::kStateBytes), and 748 bytes of
  // counts, size, shares and moments: a count of leaves the bytes cannot
  // hold is refused before they are made.
  const uint64_t distribution_bytes =
      settings_.distribution == GuideDistributionKind::kMixture ? VmfMixture::kStateBytes : 112;
  uint64_t leaf_count = 0;
  std::vector<Node> nodes = read_spatial_nodes(in, 2 * kBins * distribution_bytes + 748, &leaf_count, "a guiding tree");
  std::vector<Leaf> leaves(leaf_count, Leaf(settings_.distribution));
  for (Leaf& l : leaves) {
    for (uint32_t b = 0; b < kBins; ++b) {
      l.sampled[b].read_state(in);
      l.learning[b].read_state(in);
    }
    l.records = in.get<uint64_t>();
    l.size = in.get<Vec3>();
    l.alpha = in.get<decltype(l.alpha)>();
    l.moment = in.get<decltype(l.moment)>();
    l.moment_records = in.get<decltype(l.moment_records)>();
    // (records halve at each split: a count far beyond any render's would
    // split a leaf into more than memory holds.)
    const bool fine = l.records < (uint64_t(1) << 40) && l.size.x > 0.f && l.size.y > 0.f && l.size.z > 0.f &&
                      std::isfinite(l.size.x + l.size.y + l.size.z) &&
                      std::all_of(l.alpha.begin(), l.alpha.end(), [](float a) { return a >= 0.f && a <= 1.f; }) &&
                      std::all_of(l.moment.begin(), l.moment.end(), [](const auto& m) {
                        return std::all_of(m.begin(), m.end(), [](const FixedSum& x) { return x.sane_total(); });
                      });
    if (!fine) throw std::runtime_error("a guiding leaf with " + std::to_string(l.records) + " records, or a size or share that cannot be");
  }
  const FixedSum drawn = in.get<FixedSum>(), bsdf = in.get<FixedSum>();
  const uint64_t guided = in.get<uint64_t>();
  const bool stopped = in.get<uint8_t>() != 0;
  const uint32_t stopped_after = in.get<uint32_t>();
  const double share = in.get<double>();
  const bool verdict_fine =
      drawn.sane_total() && bsdf.sane_total() && (share == -1.0 || (share >= 0.0 && std::isfinite(share))) &&
      (stopped ? stopped_after >= kFirstJudged && stopped_after <= 62 && settings_.stop_where_unpaid
               : stopped_after == 0);
  if (!verdict_fine) throw std::runtime_error("a guiding tree's verdict on whether it pays cannot be");
  nodes_ = std::move(nodes);
  leaves_ = std::move(leaves);
  trained_ = trained;
  image_drawn_ = drawn, image_bsdf_ = bsdf;
  image_guided_ = guided;
  stopped_ = stopped, stopped_after_ = stopped_after, image_share_ = share;
  index_guide_shares();
}

}  // namespace lantern
