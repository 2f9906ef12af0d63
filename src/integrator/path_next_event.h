// The path tracer's next-event estimation, written once for a vertex on a
// surface or in a medium (integrator/vertex.h): one light sample, weighted
// against the scattering strategy by the power heuristic (Veach 1997,
// sec. 9.2). In a scene with media the weight waits for the shadow ray's
// transmittance, which the scattering strategy's density contains
// (PathTracer::media_shadow_stage). Where paths are guided, the weight
// still sees the BSDF's density alone, as the path's hits of emitters do
// (PathTracer::shade_stage): any density both sides use gives weights that
// sum to one, and the mixture's would cost a look-up per light sample.
#pragma once

#include "integrator/path_wave.h"
#include "integrator/vertex.h"
#include "integrator/volume_lights.h"
#include "light/light_sampler.h"

namespace lantern {

template <class Vertex>
void path_next_event(const Scene& sc, const LightSampler& light_sampler, PathWave& w, uint32_t slot, const Vertex& v,
                     LazyNumber u_light, Vec2 u_light2, float u_volume, int maxdepth) {
  ++w.stats.light_samples;
  const SampledWavelengths& lambda = w.lambda[slot];
  auto ls = sample_light(sc.lights, sc.shapes, sc.textures, light_sampler, v.p, v.light_sampler_normal(), u_light,
                         u_light2, lambda, u_volume);
  MediumHandle expect;
  Spectrum sigma_end(0.f);
  if (ls && ls->volume) {
    if (!volume_sample_allowed(int(w.depth), maxdepth)) return;
    complete_volume_sample(sc.lights, sc.media, &ls->L, ls->p_light, ls->light, lambda, &expect, &sigma_end);
  }
  if (!ls || is_black(ls->L)) return;
  const VertexEval e = v.evaluate(ls->wi, false);
  if (is_black(e.f)) return;
  const Vec3 o = v.ray_origin(ls->wi);
  if (!sc.media.empty()) {
    push_media_shadow_ray(w, slot, o, *ls, v.medium_towards(sc, ls->wi), ls->delta ? 0.f : ls->pdf, e.pdf_fwd,
                          w.beta[slot] * e.f * ls->L / ls->pdf, expect, sigma_end);
    return;
  }
  const float weight = ls->delta ? 1.f : power_heuristic(ls->pdf, e.pdf_fwd);
  const uint32_t r = ls->infinite ? w.shadow.push(o, ls->wi, 0.f, kInfinity, w.time[slot])
                                  : w.shadow.push(o, light_sample_target(*ls) - o, 0.f, 1.f, w.time[slot]);
  w.shadow_slot[r] = slot;
  w.shadow_contrib[r] = w.beta[slot] * e.f * ls->L * (weight / ls->pdf);
}

}  // namespace lantern
