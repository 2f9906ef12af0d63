// Shading every hit of a bounce with its concrete BSDF, and continuing a
// subpath by sampling that BSDF: the steps all wavefront integrators share.
#pragma once

#include "integrator/bdpt_mis.h"
#include "integrator/guided_scatter.h"
#include "integrator/hit.h"
#include "integrator/vertex.h"
#include "integrator/wave_stats.h"
#include "material/bsdf_kernel.h"
#include "scene/scene.h"

namespace lantern {

// Calls fn(i, bsdf) for every binned hit i, one loop per material kind.
template <class Fn>
void for_each_binned_bsdf(const HitPool& hits, const Scene& scene, Fn&& fn) {
  for (int k = 0; k < kMaterialKindCount; ++k) {
    const auto& bin = hits.bins[size_t(k)];
    if (!bin.empty())
      for_each_bsdf(MaterialKind(k), scene.materials, scene.textures, bin.data(), bin.size(),
                    hits.material.data(),
                    SurfaceAttributes{hits.p.data(), hits.ng.data(), hits.uv.data(),
                                      hits.footprint.empty() ? nullptr : hits.footprint.data(),
                                      hits.tangent.empty() ? nullptr : hits.tangent.data(), hits.lambda.data()},
                    fn);
  }
}

// The state a bidirectional subpath carries from vertex to vertex.
struct SubpathRef {
  Spectrum& beta;
  MisState& mis;
  Vec3& prev_p;
  Vec3& prev_n;
  float& eta_scale;  // radiance's 1/eta^2 factors, undone for Russian roulette
  float rr_scale;    // 1 / the throughput the subpath started with
};

// Samples the BSDF at hit i to continue a subpath (mode: radiance for eye
// subpaths, importance for light subpaths), updates throughput and MIS
// quantities, plays Russian roulette from the third vertex on, and sets the
// hit's next ray. Returns why the subpath ended (hits.alive[i] stays 0), or
// PathEnd::Count when it goes on.
//
// With `guide` (an eye subpath of a guided render, docs/guiding.md) the
// direction comes from the one-sample mixture of the BSDF and the guide
// (integrator/guided_scatter.h), into *drawn: the throughput divides by
// the mixture's density, but the MIS quantities keep the BSDF's. Weights
// formed from densities that every strategy computes alike for a path sum
// to one over the strategies, and each strategy's estimate divides by its
// own true density, so the estimator stays unbiased (the guided path
// tracer's next-event weights rest on the same argument). A strategy with
// weight has density: the mixture is at least alpha times the BSDF's.
template <class BSDF>
PathEnd continue_subpath(const BSDF& bsdf, TransportMode mode, HitPool& hits, uint32_t i, const Frame& frame,
                         const Vec3& wo, LazyNumber uc, Vec2 u2, LazyNumber u_rr, uint32_t depth, SubpathRef sub,
                         MisPower mis, const GuideAt* guide = nullptr, ScatterSample* drawn = nullptr) {
  const bool importance = mode == TransportMode::Importance;
  const TransportMode reverse = importance ? TransportMode::Radiance : TransportMode::Importance;
  Vec3 wi;
  float pdf_fwd, pdf_rev, etap;
  bool specular, transmission;
  if (guide) {
    auto s = sample_scatter(bsdf, frame, wo, *guide, uc, u2, mode);
    // (a direction only the guide draws has no density for MIS: its weight is 0)
    if (!s || !(s->bsdf_pdf > 0.f)) return PathEnd::Absorbed;
    *drawn = *s;
    wi = s->wi;
    sub.beta *= importance ? s->weight * shading_normal_correction(hits.wo[i], wi, hits.ng[i], hits.ns[i]) : s->weight;
    pdf_fwd = s->bsdf_pdf;
    pdf_rev = s->specular ? s->pdf : bsdf.pdf(s->wi_local, wo, reverse);
    etap = s->etap, specular = s->specular, transmission = s->transmission;
  } else {
    auto bs = bsdf.sample_f(wo, reads_component_number<BSDF>() ? uc() : 0.f, u2, mode);
    if (!bs || bs->pdf == 0.f || is_black(bs->f)) return PathEnd::Absorbed;
    wi = frame.from_local(bs->wi);
    float scale = std::fabs(bs->wi.z) / bs->pdf;
    if (importance) scale *= shading_normal_correction(hits.wo[i], wi, hits.ng[i], hits.ns[i]);
    sub.beta *= bs->f * scale;
    pdf_fwd = bs->pdf_is_proportional ? bsdf.pdf(wo, bs->wi, mode) : bs->pdf;
    pdf_rev = bs->specular ? bs->pdf : bsdf.pdf(bs->wi, wo, reverse);
    etap = bs->etap, specular = bs->specular, transmission = bs->transmission;
  }
  mis_after_scatter(sub.mis, vertex_cos(hits.ng[i], hits.error_scale[i], tangent_or_null(hits.tangent, i), wi), pdf_fwd,
                    pdf_rev, specular, mis);
  if (!importance && transmission) sub.eta_scale *= sqr(etap);
  if (!survives_roulette(sub.beta, sub.eta_scale, sub.rr_scale, depth >= 2, u_rr)) return PathEnd::Roulette;
  if (!is_finite(sub.beta)) return PathEnd::Absorbed;
  hits.alive[i] = 1;
  sub.prev_p = hits.p[i];
  sub.prev_n = hits.ns[i];
  hits.next_o[i] = offset_ray_origin(hits.p[i], hits.ng[i], hits.error_scale[i], wi);
  hits.next_d[i] = wi;
  return PathEnd::Count;
}

}  // namespace lantern
