// Continuing a path by one-sample MIS between the BSDF and the guiding
// field's distribution at the vertex (Müller et al. 2017, sec. 5), the
// BSDF chosen with probability α. The estimate of a direction wi is
//   f(wi) |cos| / p_mix(wi),  p_mix = α p_bsdf + (1 - α) p_guide,
// whichever technique drew it (Veach 1997, sec. 9.2.4, balance heuristic).
// α is the field's, per leaf and normal (guiding/sd_tree.h: chosen by the
// samples' second moment).
//
// Layered BSDFs return a stochastic f with a sample whose density they do
// not know (BSDFSample::pdf_is_proportional); their pdf() is an estimate,
// but a deterministic function of the directions. The balance weights are
// formed with that pdf and still sum to one, and each technique's estimate
// is divided by its own true density (the BSDF's sample weight f/pdf is an
// unbiased estimate of f over its density), so the mixture stays unbiased:
// the BSDF technique's estimate is (f |cos| / pdf) * p_bsdf / p_mix.
//
// A delta component can only come from the BSDF technique: its estimate is
// divided by α, and no density is mixed.
#pragma once

#include <optional>

#include "guiding/guide_distribution.h"
#include "material/bsdf_common.h"
#include "math/equal_area.h"
#include "math/frame.h"
#include "math/lazy_number.h"
#include "medium/henyey_greenstein.h"

namespace lantern {

// The guiding distribution at one vertex; tree null where there is none
// (a BSDF that is all delta, a leaf without energy, before learning).
struct GuideAt {
  const GuideDistribution* tree = nullptr;
  float alpha = 1.f;  // the BSDF's share
  Vec3 p{0.f};        // the vertex's position (what a mixture's lobes are re-aimed from)

  explicit operator bool() const { return tree != nullptr; }
  // Solid-angle density of a unit direction (world).
  float pdf(const Vec3& w) const { return tree->sphere_pdf(w, p); }
  // A unit direction drawn from the guide, and its density.
  Vec3 sample(Vec2 u, float* pdf) const { return tree->sample_direction(u, p, pdf); }
  float mix(float bsdf_pdf, float guide_pdf) const { return alpha * bsdf_pdf + (1.f - alpha) * guide_pdf; }
};

struct ScatterSample {
  Vec3 wi{0.f};          // world
  Vec3 wi_local{0.f};    // shading frame
  Spectrum weight{0.f};  // f |cos| / density: what the throughput is multiplied by
  float pdf = 0.f;       // the density MIS uses (the mixture's; the BSDF's own for a delta sample)
  // Its parts: the BSDF's density (pdf()'s; what MIS against light
  // sampling uses) and the guide's (-1 without a guide).
  float bsdf_pdf = 0.f, guide_pdf = -1.f;
  float etap = 1.f;  // relative index along wi (1 where a guided direction refracts: roulette only reads it)
  bool specular = false, transmission = false;
};

// Draws a direction at a vertex with shading frame `frame` and outgoing
// direction wo (local). uc picks the technique and is reused by the BSDF;
// it is drawn only if one of them reads it.
template <class BSDF>
std::optional<ScatterSample> sample_scatter(const BSDF& bsdf, const Frame& frame, const Vec3& wo, const GuideAt& guide,
                                            LazyNumber u_component, Vec2 u2, TransportMode mode) {
  ScatterSample s;
  const float a = guide.alpha;
  float uc = guide || reads_component_number<BSDF>() ? u_component() : 0.f;
  if (!guide || uc < a) {
    if (guide) uc = std::min(uc / a, 0x1.fffffep-1f);
    auto bs = bsdf.sample_f(wo, uc, u2, mode);
    if (!bs || bs->pdf == 0.f || is_black(bs->f)) return std::nullopt;
    s.wi_local = bs->wi;
    s.wi = frame.from_local(bs->wi);
    s.etap = bs->etap;
    s.specular = bs->specular;
    s.transmission = bs->transmission;
    s.weight = bs->f * (std::fabs(bs->wi.z) / bs->pdf);
    s.bsdf_pdf = bs->pdf_is_proportional ? bsdf.pdf(wo, bs->wi, mode) : bs->pdf;
    if (!guide) {
      s.pdf = s.bsdf_pdf;
    } else if (bs->specular) {
      s.pdf = bs->pdf;
      s.weight /= a;
    } else {
      s.guide_pdf = guide.pdf(s.wi);
      s.pdf = guide.mix(s.bsdf_pdf, s.guide_pdf);
      if (!(s.pdf > 0.f)) return std::nullopt;
      s.weight *= s.bsdf_pdf / s.pdf;
    }
    return s;
  }
  s.wi = guide.sample(u2, &s.guide_pdf);
  s.wi_local = frame.to_local(s.wi);
  const Spectrum f = bsdf.f(wo, s.wi_local, mode);
  if (is_black(f)) return std::nullopt;
  s.bsdf_pdf = bsdf.pdf(wo, s.wi_local, mode);
  s.pdf = guide.mix(s.bsdf_pdf, s.guide_pdf);
  if (!(s.pdf > 0.f)) return std::nullopt;
  s.weight = f * (std::fabs(s.wi_local.z) / s.pdf);
  s.transmission = s.wi_local.z * wo.z < 0.f;
  return s;
}

// The same mixture at a vertex in a medium, whose "BSDF" is the phase
// function (no cosine, directions in world space). The phase technique
// samples the phase function exactly, so its estimate is p_phase / p_mix;
// the guide's is phase(wi) / p_mix too. bsdf_pdf holds the phase density
// (what MIS with light sampling and the bidirectional weights use).
inline std::optional<ScatterSample> sample_phase_scatter(const HenyeyGreenstein& phase, const Vec3& wo,
                                                         const GuideAt& guide, float uc, Vec2 u2) {
  ScatterSample s;
  if (!guide || uc < guide.alpha) {
    s.wi = phase.sample(wo, u2, &s.bsdf_pdf);
  } else {
    s.wi = guide.sample(u2, &s.guide_pdf);
    s.bsdf_pdf = phase.p(wo, s.wi);
  }
  if (!(s.bsdf_pdf > 0.f)) return std::nullopt;
  if (!guide) {
    s.pdf = s.bsdf_pdf;
    s.weight = Spectrum(1.f);
    return s;
  }
  if (s.guide_pdf < 0.f) s.guide_pdf = guide.pdf(s.wi);
  s.pdf = guide.mix(s.bsdf_pdf, s.guide_pdf);
  if (!(s.pdf > 0.f)) return std::nullopt;
  s.weight = Spectrum(s.bsdf_pdf / s.pdf);
  return s;
}

}  // namespace lantern
