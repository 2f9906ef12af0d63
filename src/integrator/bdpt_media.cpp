// The bidirectional tracer's stages for participating media: where each
// segment ends (integrator/medium_events.h) and what that adds to the MIS
// quantities, the vertices that scatter in a medium on either subpath (the
// connections they end and the phase-function sampling that continues
// them), and the response of a stored light vertex of either kind. Only
// scenes with media run these.
//
// A medium vertex differs from a surface vertex in three ways: its
// "BSDF" is the phase function (no cosine), its area measure is volume (no
// cosine in the density conversions), and rays leave it without an offset.
#include "integrator/bdpt.h"
#include "integrator/bdpt_strategies.h"
#include "integrator/bdpt_wave.h"
#include "integrator/hit.h"
#include "integrator/shade.h"
#include "integrator/volume_lights.h"
#include "light/emission.h"
#include "medium/henyey_greenstein.h"
#include "sampler/dimensions.h"

namespace lantern {

void Bdpt::segment_stage(BdptWave& w, RayKind kind, bool light_subpaths) const {
  StageTimer t(w.stats, Stage::Surface);
  const SubpathPool& sub = light_subpaths ? w.light : w.eye;
  // eye depth d reaches its vertex d along segment d - 1; light depth d along d - 1 too
  const uint32_t segment = w.depth - 1, base = dims::vertex(uint32_t(settings_.maxdepth) + 2);
  for (uint32_t i = 0; i < w.rays.count; ++i) {
    const uint32_t slot = w.active[i];
    w.ray_medium[i] = sub.medium[slot];
    w.ray_lambda[i] = w.lambda[slot];
    w.u_distance[i] = w.sampler[slot].get1d(dims::distance(base, segment, light_subpaths));
  }
  find_segment_ends(scene_, w.stream, kind, w.rays, w.ray_medium, w.u_distance, w.ray_lambda, w.ends, w.crossing);
}

// The segment's throughput and the densities it adds to the MIS quantities
// of the vertex it reached (call after mis_after_hit). Returns false when
// the subpath ends here (absorbed).
bool Bdpt::apply_segment(BdptWave& w, SubpathPool& sub, uint32_t i) const {
  const uint32_t slot = w.active[i];
  const SegmentEnds& e = w.ends;
  sub.beta[slot] *= e.weight[i];
  if (e.end[i] == SegmentEnd::Absorbed) return false;
  const float rev = mixture_density(sub.sigma_prev[slot], e.T[i]);
  mis_after_segment(sub.mis[slot], e.fwd_density[i], rev, w.mis);
  sub.sigma_prev[slot] = e.end[i] == SegmentEnd::Scatter ? e.sigma_t[i] : Spectrum(0.f);
  return true;
}

// A stored light vertex as a vertex again (integrator/vertex.h): its BSDF
// as the light subpath built it, or its phase function.
LightVertexResponse Bdpt::light_vertex_response(const LightVertexPool& v, uint32_t j, const Vec3& wi_w) const {
  LightVertexResponse r;
  if (v.in_medium(j)) {
    const MediumVertex x{HenyeyGreenstein{scene_.media.g(v.medium[j])}, v.p[j], v.wo[j], v.medium[j], v.sigma_t[j]};
    r.e = x.evaluate(-wi_w);
    r.sigma_t = x.sigma_t();
    r.target = x.ray_origin(-wi_w);
    return r;
  }
  v.bsdfs.visit(v.bsdf[j], [&](const auto& lb) {
    const Frame lf = Frame::from_z(v.ns[j]);
    const SurfaceVertex<std::decay_t<decltype(lb)>, TransportMode::Importance> x{
        lb, lf, v.p[j], v.ng[j], v.ns[j], v.wo[j], lf.to_local(v.wo[j]), v.error_scale[j],
        tangent_or_null(v.tangent, j), 0, {}};
    r.e = x.evaluate(-wi_w);
    r.cos = x.cos(wi_w);
    r.target = x.ray_origin(-wi_w);
  });
  return r;
}

// Ray i's scattering point in a medium, as a vertex.
MediumVertex Bdpt::medium_vertex(const BdptWave& w, uint32_t i) const {
  const MediumHandle m = w.ends.medium[i];
  return {HenyeyGreenstein{scene_.media.g(m)}, w.ends.p[i], -glm::normalize(w.rays.direction(i)), m, w.ends.sigma_t[i]};
}

// The third number of a volume light's point sampled from the eye vertex
// at the current depth (only scenes with emissive media read it).
float Bdpt::volume_number(const BdptWave& w, uint32_t slot) const {
  if (!scene_.media.any_emissive()) return 0.5f;
  const uint32_t maxdepth = uint32_t(settings_.maxdepth);
  return w.sampler[slot].get1d(dims::volume_point(dims::vertex(maxdepth + 2), maxdepth, w.depth, false));
}

// Completes a volume light sample of next-event estimation from the eye
// vertex at eye depth `depth` (paths ending on volume emission have at
// most maxdepth segments; a longer one gets L = 0).
void Bdpt::complete_volume_light_sample(LightSample& ls, uint32_t depth, const SampledWavelengths& lambda,
                                        VolumeSampleEnd* end) const {
  if (!volume_sample_allowed(int(depth), settings_.maxdepth)) {
    ls.L = Spectrum(0.f);
    return;
  }
  complete_volume_sample(scene_.lights, scene_.media, &ls.L, ls.p_light, ls.light, lambda, &end->medium,
                         &end->sigma_t);
}

// s = 0 at an eye vertex in an emissive medium (beta_before: the
// throughput before the segment that reached it); call after the
// vertex's MIS update. The other strategies of the same path sample its
// point on the medium's volume light: next-event estimation from the
// previous vertex (s = 1) and light subpaths from it (s >= 2, or the
// camera connection when the vertex is the first).
void Bdpt::add_volume_emission(BdptWave& w, uint32_t i, const Spectrum& beta_before) const {
  const uint32_t slot = w.active[i];
  const Vec3 x = w.ends.p[i];
  const LightPools& lights = scene_.lights;
  const int64_t light = lights.volume_light_of(w.ends.medium[i]);
  float wt = 1.f, rescaled = 0.f;
  const MisState& m = w.eye.mis[slot];
  if (light >= 0) {
    const float density = volume_light_density(scene_.lights, light, x);
    const float pos_pdf = emission_choice_.discrete_pmf(size_t(light)) * density;
    wt = w.depth == 1 ? mis_weight_hit_light_direct(m, pos_pdf, w.mis)
                      : mis_weight_hit_light(m, light_sampler_.pmf(w.eye.prev_p[slot], w.eye.prev_n[slot], uint32_t(light)) * density,
                                             pos_pdf * uniform_sphere_pdf(), w.mis, &rescaled);
  }
  const Spectrum c = beta_before * w.ends.emission[i];
  if (is_finite(c)) add_emission(w, slot, c, emission_weight(m, wt), rescaled, light >= 0 ? uint32_t(light) : kNoLight);
}

MergeKind Bdpt::light_vertex_merging(const LightVertexPool& v, uint32_t j) const {
  return v.in_medium(j) ? medium_merging() : MergeKind::Surface;
}

// Continues a subpath from a medium vertex by sampling the phase function
// (exactly: the throughput keeps its value), or on a guided eye subpath
// the mixture of it and the guide (the throughput divides by the mixture's
// density, MIS keeps the phase function's: integrator/shade.h says why).
// light: the subpath kind. *drawn: what was drawn.
PathEnd Bdpt::scatter_in_medium(BdptWave& w, SubpathPool& sub, uint32_t i, Vec2 u2, LazyNumber u_rr, bool light,
                                const GuideAt& guide, float uc, ScatterSample* drawn) const {
  const uint32_t slot = w.active[i];
  const MediumHandle m = w.ends.medium[i];
  const HenyeyGreenstein phase{scene_.media.g(m)};
  const Vec3 wo = -glm::normalize(w.rays.direction(i));
  const auto d = sample_phase_scatter(phase, wo, guide, uc, u2);
  if (!d) return PathEnd::Absorbed;
  if (drawn) *drawn = *d;
  const Vec3 wi = d->wi;
  const float pdf = d->bsdf_pdf;
  sub.beta[slot] *= d->weight;
  mis_after_scatter(sub.mis[slot], 1.f, pdf, pdf, false, w.mis, medium_merging());
  if (!survives_roulette(sub.beta[slot], sub.eta_scale[slot], light ? sub.rr_scale[slot] : settings_.eye_roulette_scale, w.depth >= 2,
                         u_rr))
    return PathEnd::Roulette;
  if (!is_finite(sub.beta[slot])) return PathEnd::Absorbed;
  w.hits.alive[i] = 1;
  sub.prev_p[slot] = w.ends.p[i];
  sub.prev_n[slot] = Vec3(0.f);
  sub.medium[slot] = m;
  w.hits.next_o[i] = w.ends.p[i];
  w.hits.next_d[i] = wi;
  return PathEnd::Count;
}

void Bdpt::eye_medium_stage(BdptWave& w) const {
  const uint32_t depth = w.depth, maxdepth = uint32_t(settings_.maxdepth);
  for (uint32_t i : w.scattered) {
    const uint32_t slot = w.active[i];
    const PathSampler& s = w.sampler[slot];
    const uint32_t dim = dims::vertex(depth);
    const MediumVertex v = medium_vertex(w, i);
    if (depth <= maxdepth && medium_merging() == MergeKind::Medium) merge_at_eye_vertex(w, slot, v);
    if (depth <= maxdepth && settings_.connections) {
      next_event(w, slot, v, LazyNumber(s, dim + dims::kEyeLightSelect), s.get2d(dim + dims::kEyeLightPosition));
      connect_light_vertices(w, slot, v);
    }
    if (w.shadow.rays.count >= kMaxPendingConnections) flush_connections(w);
    const GuidingField::Site site = guides_eye() ? guiding_->medium_site(v.p) : GuidingField::Site{};
    ScatterSample drawn;
    const PathEnd end =
        scatter_in_medium(w, w.eye, i, s.get2d(dim + dims::kEyeBsdfDirection), LazyNumber(s, dim + dims::kEyeRoulette),
                          false, site.guide, site.guide ? s.get1d(dim + dims::kEyeBsdfComponent) : 0.f, &drawn);
    if (end != PathEnd::Count) {
      ++w.stats.eye_ends[size_t(end)];
      continue;
    }
    if (guides_eye() && guiding_->learning())
      w.guide.push(slot, site.leaf, v.p, site.normal_bin, drawn.wi, drawn.pdf, drawn.bsdf_pdf, drawn.bsdf_pdf,
                   drawn.guide_pdf, w.eye.beta[slot]);
  }
}

void Bdpt::light_medium_stage(BdptWave& w) const {
  const uint32_t depth = w.depth;
  for (uint32_t i : w.scattered) {
    const uint32_t slot = w.active[i];
    const PathSampler& s = w.sampler[slot];
    const uint32_t dim = dims::vertex(depth);
    const uint32_t ld = depth + w.origin.extra_depth[slot];  // the depth path lengths count
    const MediumVertex v = medium_vertex(w, i);
    if (keeps_light_vertex(ld))
      w.vertices.push(slot, ld, w.light.beta[slot], w.light.mis[slot],
                      {.p = v.p, .wo = v.wo_world, .bsdf = {}, .medium = v.medium, .sigma_t = v.sigma,
                       .dispersed = w.light.dispersed[slot] != 0});
    connect_camera(w, slot, ld, v, lens_numbers(camera_, s, dim + dims::kLightLens));
    if (ld >= uint32_t(settings_.maxdepth)) {
      ++w.stats.light_ends[size_t(PathEnd::MaxDepth)];
      continue;
    }
    const PathEnd end = scatter_in_medium(w, w.light, i, s.get2d(dim + dims::kLightBsdfDirection),
                                          LazyNumber(s, dim + dims::kLightRoulette), true);
    if (end != PathEnd::Count) ++w.stats.light_ends[size_t(end)];
  }
}

// Traces the pending connections through the media and weights them.
void Bdpt::trace_connections(BdptWave& w) const {
  ConnectionPool& c = w.shadow;
  trace_transmittance(scene_, w.stream, c.rays, c.medium, c.lambda, c.T, c.T_mis, w.crossing);
  const bool weighted = this->weighted();
  for (uint32_t r = 0; r < c.rays.count; ++r) {
    if (c.rays.occluded(r)) continue;
    if (!c.expect[r].vacuum() && w.crossing.medium[r] != c.expect[r]) {  // not in the emitting medium
      c.rays.tfar[r] = -kInfinity;
      continue;
    }
    const float wt = weighted ? mis_weight_deferred(c.deferred[r], c.T_mis[r], w.mis) : 1.f;
    c.contrib[r] *= c.T[r] * wt;
    if (!is_finite(c.contrib[r])) c.rays.tfar[r] = -kInfinity;
    if (c.record) {
      c.tags[r].unweighted *= c.T[r];
      c.tags[r].weight = wt;
      c.tags[r].rescaled = weighted ? mis_rescaled_deferred(c.deferred[r], c.T_mis[r], w.mis) : 0.f;
    }
  }
}

}  // namespace lantern
