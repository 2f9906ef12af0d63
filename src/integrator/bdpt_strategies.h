// The bidirectional tracer's connection strategies, each written once for
// an eye or light vertex of either kind (integrator/vertex.h), in vacuum
// and in media alike:
//   s = 1       next_event              a light sample seen from eye vertex v
//   s >= 2      connect_light_vertices  eye vertex v joined to its slot's stored light vertices
//   t = 1       connect_camera          light vertex v joined to the lens
//   merges      merge_at_eye_vertex     eye vertex v merged with the wave's light vertices near it (vcm)
// (s = 0, emission found by the eye subpath, is the eye surface stage's.) Each builds a Connection:
// the shadow ray, the unweighted contribution, and the other strategies'
// two ratio sums without the densities of the connecting segment
// (DeferredMis, integrator/bdpt_mis.h). push_connection weights it at once
// in a scene without media, where those densities are 1, and otherwise
// once its transmittance is known: one weight, one code path.
//
// Included by the files whose stages instantiate them (bdpt.cpp,
// bdpt_light.cpp, bdpt_media.cpp).
#pragma once

#include "integrator/bdpt.h"
#include "integrator/bdpt_wave.h"
#include "integrator/dispersion.h"
#include "integrator/vertex.h"
#include "light/emission.h"

namespace lantern {

// In a scene without media a connection's segment adds nothing to the
// densities (its transmittance is 1): its weight is known now.
inline void Bdpt::count_light_ray(BdptWave& w, uint32_t slot) const {
  if (settings_.record_strategies) ++w.out->light_rays_by_light[w.origin.light[slot]];
}

inline void Bdpt::push_connection(BdptWave& w, uint32_t slot, const Connection& k) const {
  if (k.s >= 2) {
    ++w.stats.light_connections;
    if (k.t == 1) ++w.stats.camera_connections;
    count_light_ray(w, slot);
  }
  const float wt = w.shadow.media || !weighted() ? 1.f : mis_weight_vacuum(k.mis);
  w.shadow.push(slot, k, k.unweighted * wt, w.lambda[slot], w.time[slot]);
  if (w.shadow.record && !w.shadow.media) {  // (with media: trace_connections)
    StrategyTag& tag = w.shadow.tags[w.shadow.rays.count - 1];
    tag.weight = wt;
    tag.rescaled = weighted() ? mis_rescaled_vacuum(k.mis) : 0.f;
  }
}

// s = 1: next-event estimation from eye vertex v (Veach 1997, sec. 10.2;
// the weight's sums are Georgiev 2012's eq. 44, with the light's
// emission density towards v for the eye subpath's side).
template <class Vertex>
void Bdpt::next_event(BdptWave& w, uint32_t slot, const Vertex& v, LazyNumber u_light, Vec2 u_light2) const {
  const Scene& sc = scene_;
  ++w.stats.light_samples;
  auto ls = sample_light(sc.lights, sc.shapes, sc.textures, light_sampler_, v.p, v.light_sampler_normal(), u_light,
                         u_light2, w.lambda[slot], volume_number(w, slot));
  VolumeSampleEnd vol;
  if (ls && ls->volume) complete_volume_light_sample(*ls, w.depth, w.lambda[slot], &vol);
  if (!ls || is_black(ls->L)) return;
  const VertexEval e = v.evaluate(ls->wi);
  const float dist2 = ls->infinite ? 1.f : glm::dot(ls->p_light - v.p, ls->p_light - v.p);
  const float direct_pdf_A = light_sample_density_at_light(sc.lights, *ls, dist2);
  // A point exactly on a sphere light's silhouette (reached only through
  // rounding: a set of measure zero) has zero density per area, and its
  // MIS ratios would be 0/0.
  if (is_black(e.f) || !(direct_pdf_A > 0.f)) return;
  const float emission_fwd_A =
      emission_pdf(sc.lights, sc.shapes, sc.textures, emission_choice_, ls->light, ls->p_light, ls->n_light, -ls->wi) *
      v.cos(ls->wi) / dist2;
  Connection k;
  // (BSDF sampling cannot hit a delta light: its density is left out)
  k.mis = mis_sums_next_event(w.eye.mis[slot], ls->delta ? 0.f : ls->pdf, e.pdf_fwd, emission_fwd_A, direct_pdf_A,
                              e.pdf_rev, w.mis, v.merging(medium_merging()));
  k.mis.sigma_a = vol.sigma_t;  // an eye ray would end at a volume light's point by distance sampling
  k.mis.sigma_b = v.sigma_t();
  k.unweighted = w.eye.beta[slot] * e.f * ls->L / ls->pdf;
  k.s = 1;
  k.t = strategy_count(w.depth + 1);
  k.light_sample = true;
  k.light = ls->light;
  k.o = v.ray_origin(ls->wi);
  if (ls->infinite) {
    k.d = ls->wi;
    k.t_max = kInfinity;
  } else {
    k.d = light_sample_target(*ls) - k.o;
    k.expect = vol.medium;
  }
  if (w.shadow.media) k.start = v.medium_towards(sc, ls->wi);
  push_connection(w, slot, k);
}

// s >= 2: eye vertex v joined to each light vertex of its slot that keeps
// the path within maxdepth (Veach 1997, eq. 10.8; the weight's sums are
// Georgiev 2012's eqs. 40-41 for both subpaths).
template <class Vertex>
void Bdpt::connect_light_vertices(BdptWave& w, uint32_t slot, const Vertex& v) const {
  const uint32_t depth = w.depth, maxdepth = uint32_t(settings_.maxdepth);
  const LightVertexPool& lv = w.vertices;
  for (uint32_t n = lv.begin[slot]; n < lv.begin[slot + 1]; ++n) {
    const uint32_t j = lv.order[n];
    if (lv.depth[j] + depth > maxdepth) break;  // in depth order: the rest are deeper
    const Vec3 dir = lv.p[j] - v.p;
    const float dist2 = glm::dot(dir, dir);
    if (!(dist2 > 0.f)) continue;
    const Vec3 wi = dir / std::sqrt(dist2);
    const VertexEval e = v.evaluate(wi);
    if (is_black(e.f)) continue;
    const LightVertexResponse r = light_vertex_response(lv, j, wi);
    const Spectrum c = w.eye.beta[slot] * e.f * r.e.f * lv.beta[j] / dist2 *
                       joined_dispersion(w.eye.dispersed[slot], lv.is_dispersed(j));
    if (is_black(c)) continue;
    Connection k;
    k.unweighted = c;
    k.mis = mis_sums_connect(w.eye.mis[slot], lv.mis[j], e.pdf_fwd * r.cos / dist2, e.pdf_rev,
                             r.e.pdf_fwd * v.cos(wi) / dist2, r.e.pdf_rev, w.mis, v.merging(medium_merging()),
                             light_vertex_merging(lv, j));
    k.mis.sigma_a = r.sigma_t;
    k.mis.sigma_b = v.sigma_t();
    k.s = strategy_count(lv.depth[j] + 1);
    k.t = strategy_count(depth + 1);
    k.o = v.ray_origin(wi);
    k.d = r.target - k.o;
    if (w.shadow.media) k.start = v.medium_towards(scene_, wi);
    push_connection(w, slot, k);
  }
}

// t = 1: light vertex v (at path depth ld) joined to a point on the lens,
// a splat where it lands on the film (Veach 1997, sec. 10.2: light
// tracing as a strategy).
template <class Vertex>
void Bdpt::connect_camera(BdptWave& w, uint32_t slot, uint32_t ld, const Vertex& v, Vec2 u_lens) const {
  if (ld > uint32_t(settings_.maxdepth) || !settings_.connections) return;
  std::optional<Camera> moved;
  const Camera& camera = camera_at(camera_, w.time[slot], moved);
  auto cs = camera.sample_wi(v.p, u_lens);
  if (!cs) return;
  const VertexEval e = v.evaluate(cs->wi);
  if (is_black(e.f)) return;
  Connection k;
  k.mis = mis_sums_light_trace(w.light.mis[slot], camera.pdf_area(-cs->wi, sqr(cs->dist), v.cos(cs->wi)), e.pdf_rev,
                               w.mis, v.merging(medium_merging()));
  k.mis.sigma_a = v.sigma_t();  // a camera ray would end here by distance sampling
  k.unweighted = w.light.beta[slot] * e.f * (cs->We / cs->pdf);
  k.p_raster = cs->p_raster;
  k.s = strategy_count(ld + 1);
  k.t = 1;
  k.o = v.ray_origin(cs->wi);
  k.d = cs->p_lens - k.o;
  if (w.shadow.media) k.start = v.medium_towards(scene_, cs->wi);
  push_connection(w, slot, k);
}

// Merges (vcm, bpm, ppm): eye vertex v with the light vertices of the
// whole wave within the merging radius that it merges with, each a
// photon-mapping estimate weighted against every other strategy of its
// path. On a surface: a disk of radius r, the eye's BSDF times the light
// vertex's throughput over pi r^2 n (Georgiev et al. 2012, eq. 17). In a
// medium: a ball of volume 4/3 pi r^3 (volumetric photon mapping as a
// strategy; Jarosz et al. 2011, Křivánek et al. 2014's point-point
// estimator); both throughputs carry the scattering coefficient of their
// own vertex and the path scatters once there, so the estimate divides by
// sigma_s at the eye vertex. A merged path has lv.depth + depth segments
// (the two vertices count as one), at most maxdepth + 1 as a connected one
// has.
template <class Vertex>
void Bdpt::merge_at_eye_vertex(BdptWave& w, uint32_t slot, const Vertex& v) const {
  const uint32_t depth = w.depth, maxdepth = uint32_t(settings_.maxdepth);
  const LightVertexPool& lv = w.vertices;
  const MisState& m = w.eye.mis[slot];
  const MergeKind kind = v.merging(medium_merging());
  // The eye subpath's factor on the summed light throughputs: beta over
  // pi r^2 n on a surface; beta over sigma_s 4/3 pi r^3 n in a medium (a
  // channel without scattering none), looked up once, when needed.
  Spectrum medium_scale(-1.f);
  auto estimate = [&](const Spectrum& x) -> Spectrum {
    if constexpr (Vertex::kInMedium) {
      if (medium_scale[0] < 0.f) {
        Spectrum sigma_a, sigma_s;
        scene_.media.coefficients_at(v.medium, v.p, w.lambda[slot], &sigma_a, &sigma_s);
        for (int c = 0; c < Spectrum::kSize; ++c)
          medium_scale[c] = sigma_s[c] > 0.f ? w.eye.beta[slot][c] / sigma_s[c] * w.vm_normalization_medium : 0.f;
      }
      return medium_scale * x;
    } else {
      return w.eye.beta[slot] * x * w.vm_normalization;
    }
  };
  Spectrum sum(0.f);
  w.grid.query(lv.p, v.p, [&](uint32_t j) {
    if (lv.depth[j] + depth > maxdepth + 1) return;
    if (!v.merges_with(lv.ng[j], lv.in_medium(j) ? lv.medium[j] : MediumHandle{})) return;
    const VertexEval e = v.evaluate_merge(lv.wo[j], !settings_.photon_mapping);  // towards where the light came from
    if (is_black(e.f)) return;
    const float wt = settings_.photon_mapping ? 1.f  // the only strategy
                                              : mis_weight_merge(m, lv.mis[j], e.pdf_fwd, e.pdf_rev, kind, w.mis);
    const Spectrum light = lv.beta[j] * joined_dispersion(w.eye.dispersed[slot], lv.is_dispersed(j));
    sum += e.f * light * weight(wt);
    ++w.stats.merges;
    // (what it brings is the light subpath's too, whichever sample's pixel it lands in)
    if (learns_light()) {
      const Spectrum brought = estimate(e.f * light * weight(wt));
      if (is_finite(brought)) gather_for_light_guide(w, lv.slot[j], strategy_count(lv.depth[j] + 1), brought);
    }
    if (settings_.record_strategies) {
      const Spectrum u = estimate(e.f * light);
      const SampledWavelengths& l = w.lambda[slot];
      w.out->strategies.push_back({w.pixel[slot], Vec2(0.f), strategy_count(lv.depth[j] + 1), strategy_count(depth + 1),
                                   film_rgb(u * weight(wt), l), film_rgb(u, l), true, slot, wt, 0.f,
                                   w.origin.light[lv.slot[j]]});
    }
  });
  if (is_black(sum)) return;
  const Spectrum c = estimate(sum);
  if (is_finite(c)) w.L[slot] += c;
}

}  // namespace lantern
