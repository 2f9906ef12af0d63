// The path tracer's stages for participating media: where each segment
// ends (integrator/medium_events.h), the vertices that scatter in a medium
// (next-event estimation and phase-function sampling), and shadow rays
// weighted once their transmittance is known. Only scenes with media run
// these; every other scene runs path_tracer.cpp alone.
#include "integrator/path_tracer.h"
#include "integrator/path_next_event.h"
#include "integrator/path_wave.h"
#include "medium/henyey_greenstein.h"
#include "sampler/dimensions.h"

namespace lantern {

void PathTracer::segment_stage(PathWave& w, RayKind kind) const {
  StageTimer t(w.stats, Stage::Surface);
  const uint32_t base = dims::vertex(uint32_t(settings_.maxdepth) + 2);
  for (uint32_t i = 0; i < w.rays.count; ++i) {
    const uint32_t slot = w.active[i];
    w.ray_medium[i] = w.medium[slot];
    w.ray_lambda[i] = w.lambda[slot];
    w.u_distance[i] = w.sampler[slot].get1d(dims::distance(base, w.bounce(), false));
  }
  find_segment_ends(scene_, w.stream, kind, w.rays, w.ray_medium, w.u_distance, w.ray_lambda, w.ends, w.crossing,
                    guiding_ ? guiding_->distance_field() : nullptr);
}

// The third number of a point sampled on a volume light from the current
// vertex (only scenes with emissive media read it).
float PathTracer::volume_number(const PathWave& w, uint32_t slot) const {
  if (!scene_.media.any_emissive()) return 0.5f;
  const uint32_t maxdepth = uint32_t(settings_.maxdepth);
  return w.sampler[slot].get1d(dims::volume_point(dims::vertex(maxdepth + 2), maxdepth, w.bounce(), false));
}

// Volume emission found by distance sampling (s = 0 for a medium point):
// beta_before is the throughput before the segment. Weighted against
// next-event estimation of the same point from the previous vertex.
void PathTracer::add_volume_emission(PathWave& w, uint32_t i, const Spectrum& beta_before, float prev_pdf) const {
  const uint32_t slot = w.active[i];
  const Vec3 x = w.ends.p[i];
  float weight = 1.f;
  if (!w.prev_specular[slot]) {
    const int64_t light = scene_.lights.volume_light_of(w.ends.medium[i]);
    const Vec3 d = x - w.prev_p[slot];
    const float light_pdf = light < 0 ? 0.f
                                      : light_sampler_.pmf(w.prev_p[slot], w.prev_n[slot], uint32_t(light)) *
                                            volume_light_density(scene_.lights, light, x) * glm::dot(d, d);
    weight = power_heuristic(prev_pdf, light_pdf);
  }
  const Spectrum c = beta_before * w.ends.emission[i] * weight;
  if (is_finite(c)) w.L[slot] += c;
}

// A vertex in a medium: next-event estimation with the phase function, then
// the path goes on in a direction sampled from it (exactly, so the
// throughput does not change), or, in a guided render, from the mixture of
// it and the guide's medium distribution (integrator/guided_scatter.h).
void PathTracer::medium_scatter_stage(PathWave& w) const {
  const Scene& sc = scene_;
  const uint32_t dim = dims::vertex(w.bounce());
  for (uint32_t i : w.scattered) {
    const uint32_t slot = w.active[i];
    const PathSampler& s = w.sampler[slot];
    const Vec3 p = w.ends.p[i], wo = -glm::normalize(w.rays.direction(i));
    const MediumHandle m = w.ends.medium[i];
    const HenyeyGreenstein phase{sc.media.g(m)};
    ++w.stats.eye_vertices;
    if (guiding_ && guiding_->learning()) w.guide.push_scattered(slot, p, w.beta[slot], w.L[slot]);
    path_next_event(sc, light_sampler_, w, slot, MediumVertex{phase, p, wo, m, w.ends.sigma_t[i]},
                    LazyNumber(s, dim + dims::kEyeLightSelect), s.get2d(dim + dims::kEyeLightPosition),
                    volume_number(w, slot), settings_.maxdepth);
    const GuidingField::Site site = guides() ? guiding_->medium_site(p) : GuidingField::Site{};
    const float uc = site.guide ? s.get1d(dim + dims::kEyeBsdfComponent) : 0.f;
    const auto drawn = sample_phase_scatter(phase, wo, site.guide, uc, s.get2d(dim + dims::kEyeBsdfDirection));
    const LazyNumber u_rr(s, dim + dims::kEyeRoulette);
    if (!drawn) {
      ++w.stats.eye_ends[size_t(PathEnd::Absorbed)];
      continue;
    }
    const Vec3 wi = drawn->wi;
    w.beta[slot] *= drawn->weight;
    w.prev_pdf[slot] = drawn->bsdf_pdf;  // MIS with light sampling: the phase function's density
    w.prev_specular[slot] = 0;
    if (!survives_roulette(w.beta[slot], w.eta_scale[slot], settings_.roulette_scale, w.depth >= 2, u_rr)) {
      ++w.stats.eye_ends[size_t(PathEnd::Roulette)];
      continue;
    }
    if (!is_finite(w.beta[slot])) {
      ++w.stats.eye_ends[size_t(PathEnd::Absorbed)];
      continue;
    }
    if (guides() && guiding_->learning())
      w.guide.push(slot, site.leaf, p, site.normal_bin, wi, drawn->pdf, drawn->bsdf_pdf, drawn->bsdf_pdf,
                   drawn->guide_pdf, w.beta[slot]);
    w.hits.alive[i] = 1;
    w.prev_p[slot] = p;
    w.prev_n[slot] = Vec3(0.f);
    w.hits.next_o[i] = p;
    w.hits.next_d[i] = wi;
    w.medium[slot] = m;
  }
}

// Unblocked shadow rays with their transmittance and MIS weight: the
// scattering strategy would have had to pass the same segment, so its
// density is the BSDF's or phase function's times the probability P of
// passing it (medium_events.h).
void PathTracer::media_shadow_stage(PathWave& w) const {
  for (uint32_t r = 0; r < w.shadow.count; ++r) {
    if (w.shadow.occluded(r)) continue;
    if (!w.shadow_expect[r].vacuum() && w.crossing.medium[r] != w.shadow_expect[r]) continue;  // not in the emitting medium
    const Spectrum& T = w.shadow_T[r];
    const float light_pdf = w.shadow_light_pdf[r];
    const float weight =
        light_pdf == 0.f ? 1.f
                         : power_heuristic(light_pdf, w.shadow_scatter_pdf[r] *
                                                          mixture_density(w.shadow_sigma_end[r], w.shadow_T_mis[r]));
    const Spectrum c = w.shadow_contrib[r] * T * weight;
    if (!is_finite(c)) continue;
    w.L[w.shadow_slot[r]] += c;
    ++w.stats.light_samples_unoccluded;
  }
}

}  // namespace lantern
