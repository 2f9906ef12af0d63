// A scattering vertex of a subpath, on a surface or in a medium, as every
// strategy sees it: what it does with light along a direction (value and
// both directional densities in one call), the cosine that turns a density
// per solid angle towards it into one per area (volume in a medium), where
// a ray leaving it starts, and how it merges. The strategies of the
// integrators (integrator/bdpt_strategies.h, the path tracer's next-event
// estimation) are templates over these two types, so each is written once
// and a scene without media never instantiates the medium one.
//
// They differ in three ways (Veach 1997, sec. 8.2; Pauly et al. 2000): a
// medium vertex's "BSDF" is the phase function, with no cosine; its
// measure is volume, so no cosine enters the density conversions; and rays
// leave it from the point itself, with no offset.
#pragma once

#include "integrator/bdpt_mis.h"
#include "integrator/hit.h"
#include "material/bsdf_kernel.h"
#include "math/lazy_number.h"
#include "medium/henyey_greenstein.h"
#include "scene/scene.h"

namespace lantern {

// A vertex's response to light leaving along w (or, for the opposite
// transport, arriving from w).
struct VertexEval {
  Spectrum f{0.f};           // the BSDF times |cos| at the vertex (shading-normal corrected for importance), or the phase function
  float pdf_fwd = 0.f;  // the vertex's density of sampling w (solid angle), in its subpath's own transport
  float pdf_rev = 0.f;  // and of sampling its subpath's previous direction from w, the opposite transport
};

// Mode: radiance on eye subpaths, importance on light subpaths.
template <class BSDF, TransportMode Mode>
struct SurfaceVertex {
  const BSDF& bsdf;
  Frame frame;         // the shading frame
  Vec3 p, ng, ns;
  Vec3 wo_world, wo;   // towards the subpath's previous vertex, in world and shading space
  float error_scale;
  const Vec3* tangent;  // a curve's, else null
  uint32_t geom;        // the geometry hit (media: which medium a ray leaving it enters)
  MediumHandle arrived_in;

  static constexpr bool kInMedium = false;

  // f is zero below the surface for reflection-only BSDFs; the densities
  // are left zero then, since no strategy uses them. (The path tracer's
  // next-event estimation needs no reverse density: with_reverse false.)
  VertexEval evaluate(const Vec3& w, bool with_reverse = true) const {
    VertexEval e;
    const Vec3 wl = frame.to_local(w);
    e.f = bsdf.f(wo, wl, Mode);
    if constexpr (Mode == TransportMode::Importance) e.f *= std::fabs(wl.z) * shading_normal_correction(wo_world, w, ng, ns);
    else e.f *= std::fabs(wl.z);
    if (is_black(e.f)) return e;
    constexpr TransportMode reverse =
        Mode == TransportMode::Importance ? TransportMode::Radiance : TransportMode::Importance;
    e.pdf_fwd = bsdf.pdf(wo, wl, Mode);
    if (with_reverse) e.pdf_rev = bsdf.pdf(wl, wo, reverse);
    return e;
  }
  // Merging (vcm): the BSDF without the cosine (the light vertex's
  // throughput carries its own arrival's), and the densities only when
  // asked (ppm's merges are not weighted).
  VertexEval evaluate_merge(const Vec3& w, bool densities) const {
    VertexEval e;
    const Vec3 wl = frame.to_local(w);
    e.f = bsdf.f(wo, wl, Mode);
    if (is_black(e.f) || !densities) return e;
    constexpr TransportMode reverse =
        Mode == TransportMode::Importance ? TransportMode::Radiance : TransportMode::Importance;
    e.pdf_fwd = bsdf.pdf(wo, wl, Mode);
    e.pdf_rev = bsdf.pdf(wl, wo, reverse);
    return e;
  }
  // Only light vertices on a surface facing the same way: a thin wall's
  // other face lies within the radius but not on this surface. (A medium
  // vertex, whose ng is zero, never merges here.)
  bool merges_with(const Vec3& ng_light, MediumHandle /*medium_light*/) const { return glm::dot(ng_light, ng) > 0.f; }
  float cos(const Vec3& w) const { return vertex_cos(ng, error_scale, tangent, w); }
  Vec3 ray_origin(const Vec3& w) const { return offset_ray_origin(p, ng, error_scale, w); }
  Vec3 light_sampler_normal() const { return ns; }  // the light sampler's context
  Spectrum sigma_t() const { return Spectrum(0.f); }  // distance sampling never ends on a surface
  MergeKind merging(MergeKind /*in_media*/) const { return MergeKind::Surface; }
  // The medium a ray leaving along w travels in (scenes with media only).
  MediumHandle medium_towards(const Scene& scene, const Vec3& w) const {
    return medium_after(scene, geom, ng, w, arrived_in);
  }
};

struct MediumVertex {
  HenyeyGreenstein phase;
  Vec3 p;
  Vec3 wo_world;  // towards the subpath's previous vertex
  MediumHandle medium;
  Spectrum sigma;  // the extinction at p

  static constexpr bool kInMedium = true;

  // The phase function is its own density, both ways.
  VertexEval evaluate(const Vec3& w, bool /*with_reverse*/ = true) const {
    const float f = phase.p(wo_world, w);
    return {Spectrum(f), f, f};
  }
  VertexEval evaluate_merge(const Vec3& w, bool /*densities*/) const { return evaluate(w); }
  // Only light vertices in the same medium (a surface vertex's is vacuum).
  bool merges_with(const Vec3& /*ng_light*/, MediumHandle medium_light) const { return medium_light == medium; }
  float cos(const Vec3& /*w*/) const { return 1.f; }
  Vec3 ray_origin(const Vec3& /*w*/) const { return p; }
  Vec3 light_sampler_normal() const { return Vec3(0.f); }  // none: a point in a volume
  Spectrum sigma_t() const { return sigma; }
  MergeKind merging(MergeKind in_media) const { return in_media; }
  MediumHandle medium_towards(const Scene& /*scene*/, const Vec3& /*w*/) const { return medium; }
};

// Eye or light vertex i of a bounce's hit pool, with its BSDF.
template <TransportMode Mode, class BSDF>
SurfaceVertex<BSDF, Mode> surface_vertex(const HitPool& h, uint32_t i, const BSDF& bsdf, uint32_t geom,
                                         MediumHandle arrived_in) {
  const Frame frame = Frame::from_z(h.ns[i]);
  return {bsdf,   frame, h.p[i], h.ng[i], h.ns[i], h.wo[i], frame.to_local(h.wo[i]), h.error_scale[i],
          tangent_or_null(h.tangent, i), geom, arrived_in};
}

// Where a shadow ray towards light sample ls ends: just off the light's
// surface (or at its point, for a light without one).
inline Vec3 light_sample_target(const LightSample& ls) {
  return ls.n_light == Vec3(0.f) ? ls.p_light : offset_ray_origin(ls.p_light, ls.n_light, ls.error_scale, -ls.wi);
}

// Russian roulette (pbrt-v4's rule, scaled): a subpath survives with
// probability its throughput, times eta_scale (eye subpaths: the 1/eta^2
// factors of refraction undone) times rr_scale (light subpaths: 1 / the
// throughput they started with; the path tracer's paths: --roulette, 2 by
// default, docs/performance.md), when that is below 1 and the vertex is
// `eligible` (past the first bounces); a survivor's throughput is divided
// by it.
// Returns false when the subpath ends.
inline bool survives_roulette(Spectrum& beta, float eta_scale, float rr_scale, bool eligible, LazyNumber u_rr) {
  const float rr = max_component(beta * eta_scale) * rr_scale;
  if (rr < 1.f && eligible) {
    const float q = max_num(0.f, 1.f - rr);
    if (u_rr() < q) return false;
    beta /= 1.f - q;
  }
  return true;
}

}  // namespace lantern
