// What guided light subpaths learn (docs/guiding-light.md). A light
// subpath y0 y1 ... serves every strategy with s >= 2 light vertices:
// connections to eye vertices (t >= 2), light tracing (t = 1) and, in vcm,
// merges at its vertices. The direction drawn at vertex y_k (k >= 1)
// decides the vertices y_{k+1}, y_{k+2}, ..., so the strategies with
// s >= k + 2 are what it brought to the image. Their sum, over the
// throughput after the vertex, estimates the importance arriving back
// along that direction: the adjoint of the radiance an eye vertex's record
// estimates (Veach 1997, sec. 3.7.6).
// Learnt in the same records, trees and iterations as the radiance field,
// it steers light subpaths towards the surfaces whose light the camera's
// strategies use.
#include "integrator/bdpt.h"
#include "integrator/bdpt_wave.h"
#include "integrator/render_settings.h"
#include "light/emission.h"
#include "math/equal_area.h"

namespace lantern {

void Bdpt::prepare_light_learning(BdptWave& w, uint32_t slots) const {
  if (!learns_light()) {  // (after the last learning pass the buffers are not needed again)
    if (!w.gathered.empty()) w.light_guide = {}, w.light_guide_depth = {}, w.gathered = {};
    return;
  }
  w.light_guide.clear();
  w.light_guide_depth.clear();
  // s runs from 1 to maxdepth + 1 (and the volume lights' one more)
  w.light_strategies = uint32_t(settings_.maxdepth) + 3;
  w.gathered.assign(size_t(slots) * w.light_strategies, Spectrum(0.f));
}

void Bdpt::guide_emission(BdptWave& w, uint32_t slot, EmissionSample& es, LazyNumber u_select, Vec2 u_pos, Vec2 u_dir,
                          float* mix_pdf_dir) const {
  if (es.delta_pos || es.delta_dir || es.infinite || es.volume || es.n == Vec3(0.f)) return;
  const GuidingField::Site site = guiding_->importance_site(es.p, es.n, es.n);
  const GuideAt& guide = site.guide;
  float guide_pdf = -1.f, mix = es.pdf_dir;
  if (guide) {
    const float a = guide.alpha;
    if (u_dir.x < a) {  // the light's own distribution: the same point, u_dir's first number rescaled
      const auto again = sample_le(scene_.lights, scene_.shapes, scene_.textures, emission_choice_, u_select, u_pos,
                                   Vec2(std::min(u_dir.x / a, 0x1.fffffep-1f), u_dir.y), w.lambda[slot]);
      if (!again) {  // (the point stays: its s = 1, t = 1 strategy does not depend on the direction)
        *mix_pdf_dir = 0.f;
        return;
      }
      es = *again;
    } else {
      float drawn_pdf = 0.f;
      const Vec3 d = guide.sample(Vec2(std::min((u_dir.x - a) / (1.f - a), 0x1.fffffep-1f), u_dir.y), &drawn_pdf);
      if (!redirect_area_emission(scene_.lights, scene_.textures, es, d, w.lambda[slot])) {
        *mix_pdf_dir = 0.f;  // (not an area light's sample: its direction was drawn for the guide's share)
        return;
      }
      guide_pdf = drawn_pdf;
    }
    if (guide_pdf < 0.f) guide_pdf = guide.pdf(es.d);
    // (a direction only the guide draws has no density for MIS: its
    // weight is 0, and the subpath goes no further than its first point)
    if (!(es.pdf_dir > 0.f) || is_black(es.Le)) {
      *mix_pdf_dir = 0.f;
      return;
    }
    mix = guide.mix(es.pdf_dir, guide_pdf);
  }
  *mix_pdf_dir = mix;
  if (guiding_->learning()) {
    const float cos_light = std::fabs(glm::dot(es.n, es.d));
    w.light_guide.push(
        slot, site.leaf, es.p, site.normal_bin, es.d, mix, average(es.Le) * cos_light, es.pdf_dir, guide_pdf,
        es.Le * (cos_light / (es.pdf_pos * mix) / settings_.light_subpath_rate));  // (as the subpath's beta)
    w.light_guide_depth.push_back(0);
  }
}

void Bdpt::gather_for_light_guide(BdptWave& w, uint32_t slot, uint32_t s, const Spectrum& c) {
  w.gathered[size_t(slot) * w.light_strategies + std::min(s, w.light_strategies - 1)] += c;
}

void Bdpt::make_light_guide_records(const WaveDesc& wave, BdptWave& w, WaveOutput& out) const {
  const uint32_t n = w.light_strategies;
  std::vector<Spectrum> total(wave.size(), Spectrum(0.f));
  for (uint32_t slot = 0; slot < wave.size(); ++slot)
    for (uint32_t s = 0; s < n; ++s) total[slot] += w.gathered[size_t(slot) * n + s];
  // A record's "before" is what the strategies its direction did not
  // decide brought: s <= k + 1.
  GuideVertices& g = w.light_guide;
  for (size_t v = 0; v < g.size(); ++v) {
    const uint32_t last = std::min<uint32_t>(uint32_t(w.light_guide_depth[v]) + 1, n - 1);
    Spectrum before(0.f);
    for (uint32_t s = 0; s <= last; ++s) before += w.gathered[size_t(g.slot[v]) * n + s];
    g.L[v] = before;
  }
  g.make_records(total, guiding_->importance_tree(),
                 hash_key(settings_.seed, wave.pixels[0], wave.first_sample) ^ 0x6c69676874ULL, out.light_guide);
}

}  // namespace lantern
