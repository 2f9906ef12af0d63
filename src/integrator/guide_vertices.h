// The vertices a wave's paths leave for the guiding field while it learns
// (integrator/guiding_field.h): per vertex whose direction was drawn from a
// density (not a delta), its spatial leaf, position and normal's bin, the
// direction, that density, the throughput after it and the radiance the
// path had gathered by the end of its bounce. When the paths end, the radiance gathered after a vertex over
// the throughput after it is an estimate of the radiance that arrived
// along its direction (componentwise: both carry the same wavelengths).
//
// For guided distances (integrator/guided_distance.h), each vertex that
// scatters in a medium also leaves its position, the throughput it
// arrived with and the radiance its path had gathered before it: the
// radiance gathered from there on, over that throughput, is what it
// scattered back along its path per unit sigma_s.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#include "accel/ray_batch.h"
#include "guiding/guide_record.h"
#include "guiding/scatter_field.h"
#include "guiding/sd_tree.h"
#include "math/rng.h"
#include "math/spectrum.h"

namespace lantern {

struct GuideVertices {
  std::vector<uint32_t> slot, leaf;
  std::vector<Vec3> p;
  std::vector<Vec3> w;                                // the direction (unit, world)
  std::vector<uint8_t> bin;                           // of the normal (SDTree::normal_bin)
  std::vector<float> pdf, fcos, bsdf_pdf, guide_pdf;  // fcos: f |cos| of the direction (averaged over wavelengths)
  std::vector<Spectrum> beta, L;
  std::vector<uint16_t> bounce;  // the bounce each vertex was made in (end_bounce counts them)
  // Where each vertex's direction reached the scene (reached), NaN until
  // it is known: the point a mixture's parallax aims at. (Light subpaths'
  // vertices, whose bounces end_bounce does not count, learn none: with
  // their hits told, bdpt's caustics through glass were worse per sample,
  // docs/guiding-lobes.md.)
  std::vector<Vec3> next_p;
  std::vector<uint32_t> last_of_slot;  // each path's last vertex (kNone: none)
  size_t bounce_start = 0;       // the first vertex of the current bounce
  uint16_t bounces = 0;
  struct Scattered {
    std::vector<uint32_t> slot;
    std::vector<Vec3> p;
    std::vector<Spectrum> beta, L;
  } scattered;

  void clear() {
    slot.clear(), leaf.clear(), p.clear(), w.clear(), bin.clear(), pdf.clear(), fcos.clear(), bsdf_pdf.clear(),
        guide_pdf.clear(), beta.clear(), L.clear(), bounce.clear(), next_p.clear();
    std::fill(last_of_slot.begin(), last_of_slot.end(), kNone);
    bounces = 0;
    scattered.slot.clear(), scattered.p.clear(), scattered.beta.clear(), scattered.L.clear();
    bounce_start = 0;
  }
  // A vertex in a medium, before anything it scatters is added to path_L.
  void push_scattered(uint32_t s, const Vec3& position, const Spectrum& throughput, const Spectrum& path_L) {
    scattered.slot.push_back(s), scattered.p.push_back(position);
    scattered.beta.push_back(throughput), scattered.L.push_back(path_L);
  }
  size_t size() const { return slot.size(); }
  void push(uint32_t s, uint32_t spatial_leaf, const Vec3& position, uint32_t normal_bin, const Vec3& dir,
            float density, float f_cos, float density_bsdf, float density_guide, const Spectrum& throughput) {
    reached(s, position);  // (the path's vertex before sent its ray here)
    fcos.push_back(f_cos), bsdf_pdf.push_back(density_bsdf), guide_pdf.push_back(density_guide);
    slot.push_back(s), leaf.push_back(spatial_leaf), p.push_back(position), bin.push_back(uint8_t(normal_bin)),
        w.push_back(dir);
    pdf.push_back(density);
    beta.push_back(throughput);
    L.emplace_back(0.f);
    bounce.push_back(bounces);
    next_p.emplace_back(std::numeric_limits<float>::quiet_NaN());
    if (s >= last_of_slot.size()) last_of_slot.resize(size_t(s) + 1, kNone);
    last_of_slot[s] = uint32_t(size() - 1);
  }
  // The ray a path's vertex of the bounce before sent reached the scene at
  // p: a surface (the path may end there: on a light, by roulette), or the
  // point it scattered at in a medium, whose vertex push() tells of.
  void reached(uint32_t s, const Vec3& at) {
    if (s >= last_of_slot.size()) return;
    const uint32_t v = last_of_slot[s];
    if (v != kNone && bounce[v] + 1 == bounces) next_p[v] = at;
  }
  // After a bounce's light samples were added: what each path had then.
  void end_bounce(const std::vector<Spectrum>& path_L) {
    for (size_t v = bounce_start; v < size(); ++v) L[v] = path_L[slot[v]];
    bounce_start = size();
    if (bounces < UINT16_MAX) ++bounces;
  }
  // Once the paths have ended: a record per vertex into `out`. Each goes to
  // the leaf of a point drawn uniformly from a box of its own leaf's size
  // around the vertex (Müller 2019, the stochastic spatial box filter):
  // neighbouring leaves share what their edges see, and each leaf learns
  // from more records. key names the wave (random numbers by record). The
  // medium vertices' records go to `field`'s leaves, by its own leaves' box.
  void make_records(const std::vector<Spectrum>& path_L, const SDTree& tree, uint64_t key,
                    std::vector<GuideRecord>& out, const ScatterField* field = nullptr) const {
    for (size_t v = 0; v < size(); ++v) {
      const float Li = per_throughput(path_L[slot[v]] - L[v], beta[v]);
      const float energy = Li / pdf[v];
      if (!std::isfinite(energy)) continue;
      RandomStream r = RandomStream::make(key, v, 0x6775696465ULL);
      const uint32_t into = tree.leaf_of(p[v] + tree.leaf(leaf[v]).size * jitter(r));
      const GuideDistribution& learning = tree.leaf(into).learning[bin[v]];
      // A mixture learns the direction from its pivot to where the path
      // went on from, if that is known (guiding/vmf_mixture.h, parallax).
      Vec3 dir = w[v];
      float inv_distance = 0.f;
      if (learning.is_mixture() && !std::isnan(next_p[v].x)) {
        const Vec3 to = next_p[v] - learning.pivot();
        const float d = glm::length(to);
        // (a point within a micron of the pivot is taken at a micron)
        if (d > 0.f && std::isfinite(d)) dir = to / d, inv_distance = 1.f / std::max(d, 1e-6f);
      }
      const uint32_t cell = learning.cell_of(dir);
      const float estimate = fcos[v] * Li, second = estimate * estimate / pdf[v];
      const float image = sqr(average(beta[v]) * Li);
      // (a square too large for a float says nothing: SDTree::add leaves it out)
      out.push_back({into, cell, energy, second, bsdf_pdf[v], guide_pdf[v], bin[v], inv_distance, image, pdf[v]});
    }
    for (size_t v = 0; field && v < scattered.slot.size(); ++v) {
      const float S = per_throughput(path_L[scattered.slot[v]] - scattered.L[v], scattered.beta[v]);
      if (!std::isfinite(S) || is_black(scattered.beta[v])) continue;  // (nothing carried: says nothing)
      RandomStream r = RandomStream::make(key, v, 0x7363617474ULL);
      const Vec3 x = scattered.p[v];
      out.push_back(
          {field->leaf_of(x + field->size(field->leaf_of(x)) * jitter(r)), 0, S, 0.f, 0.f, -1.f, kScatteredRecord});
    }
  }
  static constexpr uint32_t kNone = UINT32_MAX;
  // What a path gathered, componentwise over the throughput it carried
  // (the channels it carried any of), averaged.
  static float per_throughput(const Spectrum& gathered, const Spectrum& throughput) {
    float sum = 0.f;
    int n = 0;
    for (int c = 0; c < kSpectrumSamples; ++c)
      if (throughput[c] > 0.f) sum += gathered[c] / throughput[c], ++n;
    return n > 0 ? max_num(sum / float(n), 0.f) : 0.f;
  }
  // A point of the box [-1/2, 1/2]^3.
  static Vec3 jitter(RandomStream& r) { return Vec3(r.get1d(), r.get1d(), r.get1d()) - 0.5f; }
  size_t memory_bytes() const {
    return vector_bytes(scattered.slot) + vector_bytes(scattered.p) + vector_bytes(scattered.beta) +
           vector_bytes(scattered.L) + vector_bytes(slot) + vector_bytes(leaf) + vector_bytes(p) + vector_bytes(w) +
           vector_bytes(bin) + vector_bytes(pdf) + vector_bytes(fcos) + vector_bytes(bsdf_pdf) +
           vector_bytes(guide_pdf) + vector_bytes(beta) + vector_bytes(L) + vector_bytes(bounce) +
           vector_bytes(next_p) + vector_bytes(last_of_slot);
  }
};

}  // namespace lantern
