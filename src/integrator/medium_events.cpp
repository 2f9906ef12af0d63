#include "integrator/medium_events.h"

#include "integrator/hit.h"

#include <cstring>

namespace lantern {

namespace {

bool is_boundary(const Scene& sc, const RayBatch& rays, uint32_t i) {
  return sc.shapes.geometries[rays.geom_id[i]].material.kind() == MaterialKind::Interface;
}

// A ray that crosses more boundaries than this (nested or coincident
// boundaries hit again and again at a grazing angle) is ended: absorbed, or
// blocked for a shadow ray. A bound, so a degenerate scene cannot hang.
constexpr int kMaxCrossings = 256;

Spectrum transmittance(const Spectrum& depth) { return exp(-depth); }

// Ray j of src (its hit included) becomes ray i of dst.
void copy_ray(RayBatch& dst, uint32_t i, const RayBatch& src, uint32_t j) {
  dst.org_x[i] = src.org_x[j], dst.org_y[i] = src.org_y[j], dst.org_z[i] = src.org_z[j];
  dst.dir_x[i] = src.dir_x[j], dst.dir_y[i] = src.dir_y[j], dst.dir_z[i] = src.dir_z[j];
  dst.tnear[i] = src.tnear[j], dst.tfar[i] = src.tfar[j];
  dst.ng_x[i] = src.ng_x[j], dst.ng_y[i] = src.ng_y[j], dst.ng_z[i] = src.ng_z[j];
  dst.u[i] = src.u[j], dst.v[i] = src.v[j];
  dst.prim_id[i] = src.prim_id[j], dst.geom_id[i] = src.geom_id[j], dst.inst_id[i] = src.inst_id[j];
}

// Prepares the crossing of boundary hit i of `rays`: the medium behind it,
// and the continued ray appended to `next` with t_max (in units of |d|).
uint32_t cross_boundary(const Scene& sc, const RayBatch& rays, uint32_t i, MediumHandle* medium, RayBatch& next,
                        float t_max) {
  const SurfacePoint sp = hit_point(sc.shapes, rays, i);
  const Vec3 d = rays.direction(i);
  *medium = sc.shapes.geometries[rays.geom_id[i]].media.after(sp.ng, d, *medium);
  // (the offset steps back along a unit direction; shadow rays' are not)
  return next.push(offset_ray_origin(sp.p, sp.ng, sp.error_scale, glm::normalize(d)), d, 0.f, t_max, rays.time[i]);
}

// The random numbers of one tracked stretch: a hash of what names it (the
// segment's uniform number, the stretch's ray and how many boundaries it
// crossed), so that they do not depend on the batch or the thread.
RandomStream stretch_stream(const Vec3& o, const Vec3& d, float u, uint32_t round) {
  auto bits = [](float f) {
    uint32_t b;
    std::memcpy(&b, &f, sizeof b);
    return uint64_t(b);
  };
  const uint64_t k = hash_key(bits(u) | uint64_t(round) << 32, bits(o.x) | bits(o.y) << 32, bits(o.z) | bits(d.x) << 32);
  return RandomStream{mix64(k ^ (bits(d.y) | bits(d.z) << 32)), 0};
}

// The density a guided scattering point was drawn with, from free flight's
// p_ff: share * p_ff + guided (integrator/guided_distance.h).
struct GuidedDensity {
  float share = 1.f, guided = 0.f;
};

// Ray i scatters in this stretch of a homogeneous medium m, of length len,
// at *s_hit by free flight, after optical depth `before`. With what the
// field learnt along it, the point is drawn again from the guided mixture:
// *s_hit and *depth (the depth up to it) follow, and the density is
// returned. u: the segment's number, for the stretch's own.
GuidedDensity guide_scatter_point(const Scene& sc, const ScatterField& field, DistanceGuide& guide, MediumHandle m,
                                  const Vec3& o, const Vec3& dir, float len, const Spectrum& before,
                                  const SampledWavelengths& l, float u, uint32_t round, float* s_hit, Spectrum* depth) {
  Spectrum sigma_a, sigma_s;
  sc.media.coefficients_at(m, o, l, &sigma_a, &sigma_s);
  const Spectrum sigma_t = sigma_a + sigma_s;
  if (!guide.build(field, o, dir, len, average(sigma_t))) return {};
  RandomStream rng = stretch_stream(o, dir, u, round);
  constexpr float a = DistanceGuide::kFreeFlightShare;
  const float u_technique = rng.get1d(), u_point = rng.get1d();
  const float t = u_technique < a ? *s_hit : guide.sample(u_point);
  // P: the probability that free flight scatters in this stretch
  float P = 0.f;
  for (int c = 0; c < kSpectrumSamples; ++c)
    P += std::exp(-before[c]) * (std::isfinite(len) ? -std::expm1(-sigma_t[c] * len) : (sigma_t[c] > 0.f ? 1.f : 0.f));
  P /= float(kSpectrumSamples);
  *s_hit = t;
  *depth = before + sigma_t * t;
  return {a, (1.f - a) * P * guide.pdf(t)};
}

// A segment's end: `depth` is the optical depth of the media with closed
// forms, `tracked` the weight and `tracked_depth` the proxy depth of the
// tracked ones. At a scattering point (sigma_t > 0) found by the closed
// forms, sigma_s completes the weight; one found by tracking has it in
// `tracked` already. A guided point's density is `guided`'s mixture.
void end_segment(SegmentEnds& out, uint32_t i, MediumHandle m, const Spectrum& depth, const Spectrum& tracked,
                 const Spectrum& tracked_depth, const Spectrum& sigma_a, const Spectrum& sigma_s, bool scatters,
                 bool by_tracking, const Spectrum& Le = Spectrum(0.f), GuidedDensity guided = {}) {
  const Spectrum T = transmittance(depth), sigma_x = sigma_a + sigma_s;
  const Spectrum T_mis = is_black(tracked_depth) ? T : transmittance(depth + tracked_depth);
  const bool closed_form_scatter = scatters && !by_tracking;
  // the density of what the closed forms sampled: scattering, or passing
  const float p_ff = mixture_density(closed_form_scatter ? sigma_x : Spectrum(0.f), T);
  const float p = closed_form_scatter ? guided.share * p_ff + guided.guided : p_ff;
  out.weight[i] = p > 0.f ? tracked * (closed_form_scatter ? T * sigma_s : T) / p : Spectrum(0.f);
  out.T[i] = T_mis;
  out.fwd_density[i] = mixture_density(sigma_x, T_mis);
  out.medium[i] = m;
  if (scatters) out.sigma_t[i] = sigma_x;
  if (!out.emission.empty())  // tracked media do not emit
    out.emission[i] = closed_form_scatter && p > 0.f ? tracked * T * sigma_a * Le / p : Spectrum(0.f);
}

}  // namespace

void find_segment_ends(const Scene& sc, RayStream& stream, RayKind kind, RayBatch& rays,
                       const std::vector<MediumHandle>& medium, const std::vector<float>& u,
                       const std::vector<SampledWavelengths>& lambda, SegmentEnds& out, CrossingScratch& s,
                       const ScatterField* distance_guide) {
  const uint32_t n = rays.count;
  if (out.end.size() < n) out.resize(rays.capacity());
  const bool emissive = sc.media.any_emissive();
  if (emissive && out.emission.size() < out.end.size()) out.emission.resize(out.end.size());
  s.medium.assign(medium.begin(), medium.begin() + n);
  s.tau.resize(n);
  s.channel.resize(n);
  s.depth.assign(n, Spectrum(0.f));
  s.tracked_weight.assign(n, Spectrum(1.f));
  s.tracked_depth.assign(n, Spectrum(0.f));
  s.owner.resize(n);
  for (uint32_t i = 0; i < n; ++i) {
    const float x = float(kSpectrumSamples) * u[i];  // a channel, and tau from the rest of u
    const int c = std::min(int(x), kSpectrumSamples - 1);
    s.channel[i] = uint8_t(c);
    s.tau[i] = -std::log1p(-std::min(x - float(c), 0x1.fffffep-1f));
    s.owner[i] = i;
  }
  uint32_t pending = n;
  for (int round = 0; pending > 0; ++round) {
    s.rays.count = 0;
    s.next.clear();
    for (uint32_t k = 0; k < pending; ++k) {
      const uint32_t i = s.owner[k];
      if (round == kMaxCrossings) {
        out.end[i] = SegmentEnd::Absorbed;
        out.weight[i] = out.T[i] = Spectrum(0.f);
        out.fwd_density[i] = 1.f;
        out.medium[i] = s.medium[i];
        if (!out.emission.empty()) out.emission[i] = Spectrum(0.f);
        continue;
      }
      const Vec3 d = rays.direction(i);
      const float d_len = glm::length(d);
      const bool hit = rays.hit(i);
      const float len = hit ? rays.tfar[i] * d_len : kInfinity;
      const MediumHandle m = s.medium[i];
      Spectrum& depth = s.depth[i];
      if (!m.vacuum()) {
        const Vec3 o = rays.origin(i), dir = d / d_len;
        float s_hit = kInfinity;
        Spectrum sigma_a, sigma_s;
        GuidedDensity guided;
        const bool by_tracking = sc.media.tracked(m);
        if (by_tracking) {
          RandomStream rng = stretch_stream(o, dir, u[i], uint32_t(round));
          const tracking::Track tr = sc.media.track(m, o, dir, len, rng.get1d(), lambda[i], rng);
          s.tracked_weight[i] *= tr.weight;
          s_hit = tr.t, sigma_a = tr.sigma_a, sigma_s = tr.sigma_s;
          float unused;
          s.tracked_depth[i] += sc.media.optical_depth(m, o, dir, 0.f, tr.real() ? tr.t : len, 0, -1.f, lambda[i], &unused);
          if (tr.saturated) s.tau[i] = kInfinity, depth = Spectrum(kInfinity);  // ends absorbed below
        } else {
          const Spectrum before = depth;
          const Spectrum stretch =
              sc.media.optical_depth(m, o, dir, 0.f, len, s.channel[i], s.tau[i], lambda[i], &s_hit);
          depth += stretch;
          if (s_hit < kInfinity && distance_guide && m.kind() == MediumKind::Homogeneous)
            guided = guide_scatter_point(sc, *distance_guide, s.distance_guide, m, o, dir, len, before, lambda[i], u[i],
                                         uint32_t(round), &s_hit, &depth);
          if (s_hit < kInfinity) sc.media.coefficients_at(m, o + dir * s_hit, lambda[i], &sigma_a, &sigma_s);
          else s.tau[i] -= stretch[s.channel[i]];
        }
        if (s_hit < kInfinity) {  // scatters inside this stretch
          out.end[i] = SegmentEnd::Scatter;
          out.p[i] = o + dir * s_hit;
          const Spectrum Le = emissive && !by_tracking ? sc.media.Le(m, out.p[i], lambda[i]) : Spectrum(0.f);
          end_segment(out, i, m, depth, s.tracked_weight[i], s.tracked_depth[i], sigma_a, sigma_s, true, by_tracking,
                      Le, guided);
          continue;
        }
      }
      if (hit && is_boundary(sc, rays, i)) {
        cross_boundary(sc, rays, i, &s.medium[i], s.rays, kInfinity);
        s.next.push_back(i);
        continue;
      }
      end_segment(out, i, m, depth, s.tracked_weight[i], s.tracked_depth[i], Spectrum(0.f), Spectrum(0.f), false, false);
      out.end[i] = !(out.fwd_density[i] > 0.f) || is_black(out.weight[i]) ? SegmentEnd::Absorbed
                   : hit                                                 ? SegmentEnd::Surface
                                                                         : SegmentEnd::Escaped;
    }
    if (s.rays.count == 0) break;
    stream.intersect(s.rays, kind);
    for (uint32_t j = 0; j < s.rays.count; ++j) copy_ray(rays, s.next[j], s.rays, j);
    pending = s.rays.count;
    std::copy(s.next.begin(), s.next.end(), s.owner.begin());
  }
}

void trace_transmittance(const Scene& sc, RayStream& stream, RayBatch& rays, const std::vector<MediumHandle>& medium,
                         const std::vector<SampledWavelengths>& lambda, std::vector<Spectrum>& T,
                         std::vector<Spectrum>& T_mis, CrossingScratch& s) {
  const uint32_t n = rays.count;
  if (T.size() < n) T.resize(rays.capacity());
  if (T_mis.size() < n) T_mis.resize(rays.capacity());
  s.medium.assign(medium.begin(), medium.begin() + n);
  s.depth.assign(n, Spectrum(0.f));
  s.tracked_weight.assign(n, Spectrum(1.f));  // the ratio tracking estimates
  s.tracked_depth.assign(n, Spectrum(0.f));
  s.rays.count = 0;
  s.next.clear();
  for (uint32_t r = 0; r < n; ++r) {
    s.rays.push(rays.origin(r), rays.direction(r), rays.tnear[r], rays.tfar[r], rays.time[r]);
    s.next.push_back(r);
  }
  RayBatch& cont = s.continued;
  for (int round = 0; s.rays.count > 0; ++round) {
    if (round == kMaxCrossings) {
      for (uint32_t j = 0; j < s.rays.count; ++j) {
        T[s.next[j]] = T_mis[s.next[j]] = Spectrum(0.f);
        rays.tfar[s.next[j]] = -kInfinity;
      }
      break;
    }
    stream.intersect(s.rays, RayKind::Shadow);
    cont.count = 0;
    s.owner.clear();
    for (uint32_t j = 0; j < s.rays.count; ++j) {
      const uint32_t r = s.next[j];
      const bool hit = s.rays.hit(j);
      const bool bounded = std::isfinite(rays.tfar[r]);
      // tfar: the hit's distance, or (a miss) the ray's own end
      const MediumHandle m = s.medium[r];
      if (!m.vacuum()) {
        const Vec3 d = s.rays.direction(j), o = s.rays.origin(j);
        const float d_len = glm::length(d), len = s.rays.tfar[j] * d_len;
        float unused;
        const Spectrum depth = sc.media.optical_depth(m, o, d / d_len, 0.f, len, 0, -1.f, lambda[r], &unused);
        if (sc.media.tracked(m)) {
          RandomStream rng = stretch_stream(o, d / d_len, rays.tfar[r], uint32_t(round));
          s.tracked_weight[r] *= sc.media.ratio_track(m, o, d / d_len, len, lambda[r], rng);
          s.tracked_depth[r] += depth;
        } else {
          s.depth[r] += depth;
        }
      }
      if (hit && is_boundary(sc, s.rays, j)) {
        const uint32_t k = cross_boundary(sc, s.rays, j, &s.medium[r], cont, kInfinity);
        if (bounded) {  // aim at the original end point, not past it
          const Vec3 end = rays.origin(r) + rays.direction(r) * rays.tfar[r];
          const Vec3 d = end - cont.origin(k);
          cont.dir_x[k] = d.x, cont.dir_y[k] = d.y, cont.dir_z[k] = d.z;
          cont.tfar[k] = 1.f;
        }
        s.owner.push_back(r);
        continue;
      }
      const Spectrum closed = transmittance(s.depth[r]);
      T[r] = hit ? Spectrum(0.f) : closed * s.tracked_weight[r];
      T_mis[r] = hit ? Spectrum(0.f) : is_black(s.tracked_depth[r]) ? closed : transmittance(s.depth[r] + s.tracked_depth[r]);
      if (is_black(T[r])) rays.tfar[r] = -kInfinity;  // reads as occluded
    }
    std::swap(s.rays, cont);
    s.next.swap(s.owner);
  }
}

void locate_media(const Scene& sc, RayStream& stream, const std::vector<Vec3>& p, const std::vector<float>& time, const Vec3& known,
                  MediumHandle known_medium, std::vector<MediumHandle>& out, CrossingScratch& s) {
  const uint32_t n = uint32_t(p.size());
  out.assign(n, known_medium);
  s.rays.count = 0;
  s.next.clear();
  for (uint32_t i = 0; i < n; ++i) {
    s.rays.push(p[i], known - p[i], 0.f, 1.f, time[i]);
    s.next.push_back(i);
  }
  RayBatch& cont = s.continued;
  for (int round = 0; s.rays.count > 0; ++round) {
    if (round == kMaxCrossings) {  // a degenerate pile of surfaces: call it vacuum (nothing emits there)
      for (uint32_t j = 0; j < s.rays.count; ++j) out[s.next[j]] = MediumHandle{};
      break;
    }
    stream.intersect(s.rays, RayKind::Shadow);
    cont.count = 0;
    s.owner.clear();
    for (uint32_t j = 0; j < s.rays.count; ++j) {
      if (!s.rays.hit(j)) continue;  // reached the known point
      const uint32_t i = s.next[j];
      const SurfacePoint sp = hit_point(sc.shapes, s.rays, j);
      const Vec3 d = s.rays.direction(j);
      const MediumInterface& mi = sc.shapes.geometries[s.rays.geom_id[j]].media;
      if (mi.transition()) {  // the side that faces p[i]
        out[i] = glm::dot(sp.ng, d) > 0.f ? mi.inside : mi.outside;
        continue;
      }
      const Vec3 o = offset_ray_origin(sp.p, sp.ng, sp.error_scale, glm::normalize(d));
      cont.push(o, known - o, 0.f, 1.f, s.rays.time[j]);  // on, through a surface that separates nothing
      s.owner.push_back(i);
    }
    std::swap(s.rays, cont);
    s.next.swap(s.owner);
  }
}

}  // namespace lantern
