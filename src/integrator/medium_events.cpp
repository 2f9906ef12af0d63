#include "integrator/medium_events.h"

#include "integrator/hit.h"

namespace lantern {

namespace {

bool is_boundary(const Scene& sc, const RayBatch& rays, uint32_t i) {
  return sc.shapes.geometries[rays.geom_id[i]].material.kind() == MaterialKind::Interface;
}

// A ray that crosses more boundaries than this (nested or coincident
// boundaries hit again and again at a grazing angle) is ended: absorbed, or
// blocked for a shadow ray. A bound, so a degenerate scene cannot hang.
constexpr int kMaxCrossings = 256;

RGB transmittance(const RGB& depth) { return RGB(std::exp(-depth.x), std::exp(-depth.y), std::exp(-depth.z)); }

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
  return next.push(offset_ray_origin(sp.p, sp.ng, sp.error_scale, glm::normalize(d)), d, 0.f, t_max);
}

}  // namespace

void find_segment_ends(const Scene& sc, RayStream& stream, RayKind kind, RayBatch& rays,
                       const std::vector<MediumHandle>& medium, const std::vector<float>& u, SegmentEnds& out,
                       CrossingScratch& s) {
  const uint32_t n = rays.count;
  if (out.end.size() < n) out.resize(rays.capacity());
  s.medium.assign(medium.begin(), medium.begin() + n);
  s.tau.resize(n);
  s.channel.resize(n);
  s.depth.assign(n, RGB(0.f));
  s.owner.resize(n);
  for (uint32_t i = 0; i < n; ++i) {
    const float x = 3.f * u[i];
    const int c = std::min(int(x), 2);
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
        out.weight[i] = out.T[i] = RGB(0.f);
        out.fwd_density[i] = 1.f;
        out.medium[i] = s.medium[i];
        continue;
      }
      const Vec3 d = rays.direction(i);
      const float d_len = glm::length(d);
      const bool hit = rays.hit(i);
      const float len = hit ? rays.tfar[i] * d_len : kInfinity;
      const MediumHandle m = s.medium[i];
      RGB& depth = s.depth[i];
      if (!m.vacuum()) {
        const int c = s.channel[i];
        const Vec3 o = rays.origin(i), dir = d / d_len;
        float s_hit;
        const RGB stretch = sc.media.optical_depth(m, o, dir, 0.f, len, c, s.tau[i], &s_hit);
        depth += stretch;
        if (s_hit < kInfinity) {  // scatters inside this stretch
          const Vec3 p = o + dir * s_hit;
          RGB sigma_a, sigma_s;
          sc.media.coefficients_at(m, p, &sigma_a, &sigma_s);
          const RGB T = transmittance(depth), sigma_x = sigma_a + sigma_s;
          const float pdf = mixture_density(sigma_x, T);
          out.end[i] = SegmentEnd::Scatter;
          out.p[i] = p;
          out.T[i] = T;
          out.weight[i] = pdf > 0.f ? T * sigma_s / pdf : RGB(0.f);
          out.fwd_density[i] = pdf;
          out.medium[i] = m;
          out.sigma_t[i] = sigma_x;
          continue;
        }
        s.tau[i] -= stretch[c];
      }
      if (hit && is_boundary(sc, rays, i)) {
        cross_boundary(sc, rays, i, &s.medium[i], s.rays, kInfinity);
        s.next.push_back(i);
        continue;
      }
      const RGB T = transmittance(depth);
      const float P = mixture_density(RGB(0.f), T);
      out.end[i] = !(P > 0.f) ? SegmentEnd::Absorbed : hit ? SegmentEnd::Surface : SegmentEnd::Escaped;
      out.T[i] = T;
      out.weight[i] = P > 0.f ? T / P : RGB(0.f);
      out.fwd_density[i] = P;
      out.medium[i] = m;
    }
    if (s.rays.count == 0) break;
    stream.intersect(s.rays, kind);
    for (uint32_t j = 0; j < s.rays.count; ++j) copy_ray(rays, s.next[j], s.rays, j);
    pending = s.rays.count;
    std::copy(s.next.begin(), s.next.end(), s.owner.begin());
  }
}

void trace_transmittance(const Scene& sc, RayStream& stream, RayBatch& rays, const std::vector<MediumHandle>& medium,
                         std::vector<RGB>& T, CrossingScratch& s) {
  const uint32_t n = rays.count;
  if (T.size() < n) T.resize(rays.capacity());
  s.medium.assign(medium.begin(), medium.begin() + n);
  s.depth.assign(n, RGB(0.f));
  s.rays.count = 0;
  s.next.clear();
  for (uint32_t r = 0; r < n; ++r) {
    s.rays.push(rays.origin(r), rays.direction(r), rays.tnear[r], rays.tfar[r]);
    s.next.push_back(r);
  }
  RayBatch& cont = s.continued;
  for (int round = 0; s.rays.count > 0; ++round) {
    if (round == kMaxCrossings) {
      for (uint32_t j = 0; j < s.rays.count; ++j) {
        T[s.next[j]] = RGB(0.f);
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
        const Vec3 d = s.rays.direction(j);
        const float d_len = glm::length(d);
        float unused;
        s.depth[r] += sc.media.optical_depth(m, s.rays.origin(j), d / d_len, 0.f, s.rays.tfar[j] * d_len, 0, -1.f, &unused);
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
      T[r] = hit ? RGB(0.f) : transmittance(s.depth[r]);
      if (is_black(T[r])) rays.tfar[r] = -kInfinity;  // reads as occluded
    }
    std::swap(s.rays, cont);
    s.next.swap(s.owner);
  }
}

}  // namespace lantern
