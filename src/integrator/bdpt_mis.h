// Bidirectional MIS in the recursive form of Georgiev 2012 ("Implementing
// Vertex Connection and Merging", merging left out): each subpath carries two
// running quantities, so the weight of any connection costs O(1) instead of a
// walk over both subpaths (Veach 1997, sec. 10.2).
//
// For a subpath vertex x_i reached from x_{i-1}, with p->(x) the area density
// of generating x from its own side and p<-(x) from the other side:
//   dVCM_i = Mis( 1 / p->(x_i) )                    (before the cos/dist update: 1 / solid-angle pdf)
//   dVC_i  = Mis( p<-(x_{i-1}) / p->(x_i) ) * (dVC_{i-1} * Mis(pdf_rev_{i-1}) + dVCM_{i-1})
// so that the weight of a strategy is 1 / (1 + sum of the other strategies'
// density ratios), each sum collected by these two numbers. Mis(x) = x^beta:
// beta = 2 is Veach's power heuristic, beta = 1 the balance heuristic.
//
// Conventions kept by every caller (they must agree for the weights of all
// strategies of one path to sum to 1):
//  - solid angle -> area conversions use the geometric normal's cosine;
//  - the camera's direction density is pbrt's whole-film 1 / (A cos^3);
//  - a camera sample traces a light subpath beyond the light with
//    probability q (the light subpath rate, 1 unless set), so every
//    strategy that uses its vertices past the light (s >= 2) is run q times
//    per camera sample and the others (s = 0, s = 1) once: Veach's sample
//    counts (1997, eq. 9.13), n_i = q or 1. s = 1, t = 1, the light's own
//    point seen by the camera, is one of those run once;
//  - Russian roulette is left out of the densities (as in pbrt): weights stay
//    a partition of unity, only slightly less optimal;
//  - a specular (delta) vertex is never connected: sampling through it sets
//    dVCM = 0, and dVC carries the chain on.
#pragma once

#include "integrator/medium_events.h"
#include "math/common.h"

namespace lantern {

// Where a vertex may merge (vcm): on a surface (a disk of radius r), in a
// medium (a ball of radius r), or not at all (specular, or merging off).
enum class MergeKind : uint8_t { None, Surface, Medium };

struct MisPower {
  float beta = 2.f;
  // Vertex merging (vcm; Georgiev et al. 2012): Mis(eta), eta the merging
  // strategies' density relative to connecting: pi r^2 n on a surface,
  // 4/3 pi r^3 n in a medium (n light subpaths merged with, radius r).
  // Zero without merging, which leaves every other quantity as bdpt has it.
  float vm_weight = 0.f, vm_medium = 0.f;
  // 1 when connections are strategies too (bdpt, vcm), 0 when merges are
  // all there is (bpm, ppm).
  float connect = 1.f;
  // The light subpath rate q's count ratios: Mis(q), what a strategy that
  // needs a light subpath weighs against one that does not, and Mis(1 / q)
  // the other way (both 1 when every camera sample traces one).
  float with_light = 1.f, without_light = 1.f;
  float operator()(float x) const { return beta == 2.f ? x * x : x; }
  float vm(MergeKind k) const { return k == MergeKind::Surface ? vm_weight : k == MergeKind::Medium ? vm_medium : 0.f; }
};

// dVM differs from Georgiev's: it is his times Mis(eta), so that merges of
// both kinds (two etas) add up in one sum; each merge weight divides by its
// own Mis(eta) (mis_weight_merge).
struct MisState {
  float dVCM = 0.f;
  float dVC = 0.f;
  float dVM = 0.f;  // vcm only: the merging strategies' sum (with connections: dVC itself)
  // A light subpath's share of dVCM and dVC that stands for strategies run
  // without it (s = 0 and s = 1, from mis_light_start): what a change of
  // the light subpath rate rescales (light_subpath_rate.h measures with
  // it). Zero on eye subpaths.
  float start_dVCM = 0.f, start_dVC = 0.f;
};

// Eye subpath from a camera ray whose direction has (whole-film) solid-angle
// density pdf_dir_W.
inline MisState mis_camera_start(float pdf_dir_W, MisPower mis) { return {mis(1.f / pdf_dir_W), 0.f}; }

// Light subpath leaving the light: direct_pdf_A is the density with which
// next-event estimation would pick the same light point (as seen from the
// first hit), emission_pdf_W = p_pos * p_dir * pmf, cos_light at the light
// (1 for lights at infinity). Delta lights cannot be hit by eye subpaths.
// Both quantities stand for strategies without a light subpath (s = 0
// and s = 1), which every strategy using this one weighs by Mis(1 / q).
inline MisState mis_light_start(float direct_pdf_A, float emission_pdf_W, float cos_light, bool delta_light,
                                MisPower mis) {
  const float dVC = delta_light ? 0.f : mis(cos_light / emission_pdf_W) * mis.without_light;
  const float dVCM = mis(direct_pdf_A / emission_pdf_W) * mis.without_light;
  return {dVCM, dVC, dVC * mis.connect, dVCM, dVC};
}

// After a ray of squared length dist2 hits a surface at cosine cos_in. The
// first segment of a light subpath from infinity has no length (its
// positional density is already per area on the disk): apply_dist = false.
inline void mis_after_hit(MisState& m, float dist2, float cos_in, bool apply_dist, MisPower mis) {
  const float c = mis(cos_in);
  if (apply_dist) {
    const float d = mis(dist2);
    m.dVCM *= d;
    m.start_dVCM *= d;
  }
  m.dVCM /= c;
  m.start_dVCM /= c;
  m.dVC /= c;
  m.start_dVC /= c;
  m.dVM /= c;
}

// After sampling a direction with density pdf_fwd (pdf_rev: the density of
// the opposite sampling) leaving at cosine cos_out, from a vertex that
// merges as `kind` says (its merge adds Mis(eta) of its kind to dVC and dVM).
inline void mis_after_scatter(MisState& m, float cos_out, float pdf_fwd, float pdf_rev, bool specular, MisPower mis,
                              MergeKind kind = MergeKind::Surface) {
  if (specular) {
    m.dVCM = m.start_dVCM = 0.f;
    m.dVC *= mis(cos_out);  // pdf_fwd == pdf_rev for every delta lobe here
    m.start_dVC *= mis(cos_out);
    m.dVM *= mis(cos_out);
  } else {
    const float f = mis(cos_out / pdf_fwd), vm = mis.vm(kind), rev = mis(pdf_rev);
    m.dVM = f * (m.dVM * rev + m.dVCM * mis.connect + vm);
    m.dVC = f * (m.dVC * rev + m.dVCM + vm);
    m.start_dVC = f * (m.start_dVC * rev + m.start_dVCM);
    m.dVCM = mis(1.f / pdf_fwd);
    m.start_dVCM = 0.f;
  }
}

// A connection's segment is not sampled, but the strategies that would have
// sampled it by distance sampling have densities that contain its
// transmittance, known once its shadow ray is traced. So a connection
// keeps the other strategies' two ratio sums without those densities (a:
// the strategy whose distance sampling ends at the end with extinction
// sigma_a, zero at a surface; b likewise) and is weighted afterwards.
// Every connection strategy below is these two sums (in vacuum the
// weight of Veach's eq. 10.9 in the recursive form: mis_weight_vacuum).
struct DeferredMis {
  float a = 0.f, b = 0.f;
  Spectrum sigma_a{0.f}, sigma_b{0.f};
  // The fractions of a and b that stand for strategies of the other
  // count class (the conventions above: those run once per camera sample
  // if this one needs a light subpath, and the other way round), which a
  // change of the light subpath rate rescales.
  float a_rescaled = 0.f, b_rescaled = 0.f;
};
inline float mis_weight_deferred(const DeferredMis& d, const Spectrum& T, MisPower mis) {
  return 1.f / (1.f + d.a * mis(mixture_density(d.sigma_a, T)) + d.b * mis(mixture_density(d.sigma_b, T)));
}
// The same in vacuum, where every segment's transmittance is 1 and so are
// both mixture densities (mixture_density gives exactly 1 there).
inline float mis_weight_vacuum(const DeferredMis& d) { return 1.f / (1.f + d.a + d.b); }
// The part of the weight's sum of ratios that the light subpath rate
// rescales (DeferredMis::a_rescaled), once the transmittance is known.
inline float mis_rescaled_deferred(const DeferredMis& d, const Spectrum& T, MisPower mis) {
  return d.a * d.a_rescaled * mis(mixture_density(d.sigma_a, T)) + d.b * d.b_rescaled * mis(mixture_density(d.sigma_b, T));
}
inline float mis_rescaled_vacuum(const DeferredMis& d) { return d.a * d.a_rescaled + d.b * d.b_rescaled; }

// What a connection weighs the strategies of one of its subpaths by,
// relative to itself, before the factor for the connection's own segment:
// m and pdf_rev_W are that subpath's quantities at the connected vertex and
// its density back towards its previous vertex; merging at that vertex
// (as `end` says) is one of them.
inline float mis_connection_sum(const MisState& m, float pdf_rev_W, MergeKind end, MisPower mis) {
  return mis.vm(end) + m.dVCM + m.dVC * mis(pdf_rev_W);
}
// The fraction of a light vertex's connection sum (above) that stands for
// strategies without a light subpath (s = 0, 1).
inline float mis_start_fraction(const MisState& m, float pdf_rev_W, float sum, MisPower mis) {
  return sum > 0.f ? (m.start_dVCM + m.start_dVC * mis(pdf_rev_W)) / sum : 0.f;
}

// s = 0: the eye subpath hit an emitter. direct_pdf_A: next-event density of
// that light point from the previous eye vertex; emission_pdf_W: density of
// the light emitting towards the previous eye vertex.
// The dVC sum is of strategies with s >= 2, which need a light subpath:
// *rescaled, if asked for, is its ratio sum (DeferredMis::a_rescaled).
inline float mis_weight_hit_light(const MisState& eye, float direct_pdf_A, float emission_pdf_W, MisPower mis,
                                  float* rescaled = nullptr) {
  const float with_light = mis(emission_pdf_W) * eye.dVC * mis.with_light;
  if (rescaled) *rescaled = with_light;
  return 1.f / (1.f + mis(direct_pdf_A) * eye.dVCM + with_light);
}

// s = 0 for a light seen straight from the camera: the only other strategy
// is light tracing from the light's own vertex (s = 1, t = 1), whose density
// is the light's positional one.
inline float mis_weight_hit_light_direct(const MisState& eye, float emission_pos_pdf_A, MisPower mis) {
  return 1.f / (1.f + mis(emission_pos_pdf_A) * eye.dVCM);
}

// s = 0 without connections (bpm, ppm: connect = 0, so no connection's
// ratio enters any merge's weight): the emitter found counts only if no
// merge samples the same path, that is if the eye subpath has passed no
// vertex that merges, the only vertices that add to dVM (Georgiev's
// technical report, "Implementing Vertex Connection and Merging", sec. 2).
inline float mis_weight_hit_light_merging_only(const MisState& eye) { return eye.dVM == 0.f ? 1.f : 0.f; }

// s = 1: next-event estimation. light_pdf_W: the light sample's solid-angle
// density (0 for delta lights, which BSDF sampling cannot hit); bsdf_pdf_W:
// BSDF density of the same direction; emission_fwd_A: the light's emission
// density towards the eye vertex, per area there; direct_pdf_A: the light
// sample's density per area on the light; eye_rev_W: BSDF density from the
// light direction back to the previous eye vertex.
inline DeferredMis mis_sums_next_event(const MisState& eye, float light_pdf_W, float bsdf_pdf_W, float emission_fwd_A,
                                       float direct_pdf_A, float eye_rev_W, MisPower mis,
                                       MergeKind eye_merge = MergeKind::Surface) {
  DeferredMis d;
  d.a = light_pdf_W > 0.f ? mis(bsdf_pdf_W / light_pdf_W) : 0.f;
  // (s >= 2 all: they need a light subpath)
  d.b = mis(emission_fwd_A / direct_pdf_A) * mis_connection_sum(eye, eye_rev_W, eye_merge, mis) * mis.with_light;
  d.b_rescaled = 1.f;
  return d;
}

// s, t >= 2: connection of an eye vertex and a light vertex. eye_fwd_A: the
// eye vertex's BSDF density towards the light vertex, per area there;
// light_fwd_A likewise the other way; *_rev_W: each vertex's density from
// the connection back to its own subpath's previous vertex.
inline DeferredMis mis_sums_connect(const MisState& eye, const MisState& light, float eye_fwd_A, float eye_rev_W,
                                    float light_fwd_A, float light_rev_W, MisPower mis,
                                    MergeKind eye_merge = MergeKind::Surface, MergeKind light_merge = MergeKind::Surface) {
  DeferredMis d;
  const float light_sum = mis_connection_sum(light, light_rev_W, light_merge, mis);
  d.a = mis(eye_fwd_A) * light_sum;
  d.b = mis(light_fwd_A) * mis_connection_sum(eye, eye_rev_W, eye_merge, mis);
  d.a_rescaled = mis_start_fraction(light, light_rev_W, light_sum, mis);
  return d;
}

// t = 1: a light vertex connected to the camera. camera_pdf_A: the camera's
// direction density towards it, per area there.
inline DeferredMis mis_sums_light_trace(const MisState& light, float camera_pdf_A, float light_rev_W, MisPower mis,
                                        MergeKind light_merge = MergeKind::Surface) {
  DeferredMis d;
  const float light_sum = mis_connection_sum(light, light_rev_W, light_merge, mis);
  d.a = mis(camera_pdf_A) * light_sum;
  d.a_rescaled = mis_start_fraction(light, light_rev_W, light_sum, mis);
  return d;
}

// Merging an eye vertex with a light vertex within the radius (vcm), on
// a surface or in a medium (kind): eye_fwd_W is the eye vertex's density
// of sampling the direction the light arrived from, eye_rev_W the density
// of the reverse (from there back towards the eye subpath's previous
// vertex). The eye vertex's and the light vertex's quantities are those at
// arrival. The other strategies' ratios to this merge are the sums over
// Mis(eta) of this kind: 1 / (1 + sums / Mis(eta)).
inline float mis_weight_merge(const MisState& eye, const MisState& light, float eye_fwd_W, float eye_rev_W,
                              MergeKind kind, MisPower mis) {
  const float others = (light.dVCM + eye.dVCM) * mis.connect + light.dVM * mis(eye_fwd_W) + eye.dVM * mis(eye_rev_W);
  if (!(others > 0.f)) return 1.f;  // the only strategy of its path
  const float vm = mis.vm(kind);
  return vm / (vm + others);
}

// s = 1, t = 1: the light's own vertex connected to the camera; the other
// strategy is the camera ray hitting the light (impossible for delta lights).
inline DeferredMis mis_sums_light_origin(float camera_pdf_A, float emission_pos_pdf_A, bool delta_pos, MisPower mis) {
  DeferredMis d;
  d.a = delta_pos ? 0.f : mis(camera_pdf_A / emission_pos_pdf_A);
  return d;
}

// Participating media (docs/media.md). A segment sampled by distance
// sampling adds to the density of the vertex it ends at the probability
// (surface, infinity) or density (medium point) of ending there, fwd
// below, and to the reverse density of the vertex it started from the same
// for the opposite direction, rev. After mis_after_hit:
inline void mis_after_segment(MisState& m, float fwd, float rev, MisPower mis) {
  const float f = mis(fwd), r = mis(rev / fwd);
  m.dVCM /= f;
  m.start_dVCM /= f;
  m.dVC *= r;
  m.start_dVC *= r;
  m.dVM *= r;
}


}  // namespace lantern
