#include "light/light_sampler.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <chrono>
#include <stdexcept>

#include "entity/shapes.h"
#include "geometry/surface.h"

namespace lantern {

namespace {

LightBounds triangle_bounds(const TriangleMesh& m, uint32_t prim, const AreaLight& a) {
  LightBounds b;
  const glm::uvec3 t = m.triangle(prim);
  for (uint32_t v : {t.x, t.y, t.z}) {
    b.lo = glm::min(b.lo, m.positions[v]);
    b.hi = glm::max(b.hi, m.positions[v]);
  }
  // The emitting side follows the geometric normal as the surface point
  // orients it; with vertex normals that can differ across the triangle,
  // and then both sides count.
  const Vec3 n0 = triangle_point(m, prim, 0.f, 0.f).ng, n1 = triangle_point(m, prim, 1.f, 0.f).ng,
             n2 = triangle_point(m, prim, 0.f, 1.f).ng, nc = triangle_point(m, prim, 1.f / 3.f, 1.f / 3.f).ng;
  const bool consistent = glm::dot(n0, nc) > 0.f && glm::dot(n1, nc) > 0.f && glm::dot(n2, nc) > 0.f;
  b.w = nc;
  b.cos_theta_o = 1.f;
  b.cos_theta_e = 0.f;  // cos(pi / 2): diffuse emission
  b.two_sided = a.two_sided || !consistent;
  return b;
}

// A curved patch's normals lie in the cone its corners' normals span (dp/du
// x dp/dv is affine in (u, v)).
LightBounds patch_bounds(const BilinearPatchSet& s, uint32_t prim, const AreaLight& a) {
  LightBounds b;
  const PatchCorners c = patch_corners(s, prim);
  b.lo = glm::min(glm::min(c.p00, c.p10), glm::min(c.p01, c.p11));
  b.hi = glm::max(glm::max(c.p00, c.p10), glm::max(c.p01, c.p11));
  const Vec3 n[4] = {bilinear_normal(s, prim, Vec2(0, 0)), bilinear_normal(s, prim, Vec2(1, 0)),
                     bilinear_normal(s, prim, Vec2(0, 1)), bilinear_normal(s, prim, Vec2(1, 1))};
  const Vec3 sum = n[0] + n[1] + n[2] + n[3];
  b.w = glm::length(sum) > 0.f ? glm::normalize(sum) : Vec3(0, 0, 1);
  b.cos_theta_o = 1.f;
  for (const Vec3& ni : n) b.cos_theta_o = min_num(b.cos_theta_o, glm::dot(b.w, ni));
  if (!(glm::length(sum) > 0.f)) b.cos_theta_o = -1.f;
  b.cos_theta_e = 0.f;  // diffuse emission
  b.two_sided = a.two_sided;
  return b;
}

}  // namespace

// The bounds' "power" is what makes importance (phi cos / d^2) estimate
// the irradiance a light gives: intensity for point and spot lights, and
// radiance times the area seen at once for area lights (a sphere shows at
// most a disk of its radius). Emitted power instead would favour a spot
// light by 2 / (1 - cos theta) and a sphere by 4 over what they deliver.
LightBounds light_bounds(const LightPools& L, const ShapePools& shapes, const TexturePools& tex, uint32_t light) {
  const LightRef r = L.all[light];
  auto avg = [](const RGB& c) { return std::max((c[0] + c[1] + c[2]) / 3.f, 0.f); };
  LightBounds b;
  switch (r.kind) {
    case LightKind::Area: {
      const AreaLight& a = L.area[r.index];
      const Geometry& g = shapes.geometries[a.geometry];
      const float mean = a.image < 0 ? 1.f : tex.image_mean(a.image);
      if (g.kind == ShapeKind::Mesh) {
        b = triangle_bounds(shapes.meshes[g.index], a.primitive, a);
        b.phi = avg(a.L) * mean * a.area;
      } else if (g.kind == ShapeKind::Bilinear) {
        b = patch_bounds(shapes.patches[g.index], a.primitive, a);
        b.phi = avg(a.L) * mean * a.area;
      } else if (g.kind == ShapeKind::Quadric) {
        const Quadric& q = shapes.quadrics[g.index];
        quadric_bounds(q, &b.lo, &b.hi);
        // A disk faces one way; a sphere or cylinder shows about a quarter
        // (1 / pi) of its area at once.
        const bool disk = q.kind == QuadricKind::Disk;
        if (disk) b.w = quadric_point(q, Vec2(0.f)).ng;
        b.cos_theta_o = disk ? 1.f : -1.f;
        b.cos_theta_e = 0.f;
        b.two_sided = a.two_sided;
        const float seen = disk ? 1.f : q.kind == QuadricKind::Sphere ? 0.25f : kInvPi;
        b.phi = avg(a.L) * mean * a.area * seen;
      } else {
        const Sphere& s = shapes.spheres[g.index];
        b.lo = s.center - Vec3(s.radius);
        b.hi = s.center + Vec3(s.radius);
        b.cos_theta_o = -1.f;  // normals in every direction
        b.cos_theta_e = 0.f;
        b.two_sided = a.two_sided;
        b.phi = avg(a.L) * mean * kPi * sqr(s.radius);
      }
      return b;
    }
    case LightKind::Point:
      b.lo = b.hi = L.point[r.index].p;
      b.cos_theta_o = -1.f;  // every direction
      b.cos_theta_e = 0.f;
      b.phi = point_mean_intensity(L, L.point[r.index]);  // a profile's light bounded as if isotropic
      return b;
    case LightKind::Spot: {
      // Light leaves within the falloff's end angle of the axis: a cone of
      // theta_start around it, widened by the rest.
      const SpotLight& s = L.spot[r.index];
      b.lo = b.hi = s.p;
      b.w = s.frame.n;
      b.cos_theta_o = s.cos_falloff_start;
      const float te = std::acos(glm::clamp(s.cos_falloff_end, -1.f, 1.f)) -
                       std::acos(glm::clamp(s.cos_falloff_start, -1.f, 1.f));
      b.cos_theta_e = std::cos(std::max(te, 0.f));
      b.phi = avg(s.I);
      return b;
    }
    case LightKind::Volume: {  // isotropic from every point of its box
      const VolumeLight& v = L.volume[r.index];
      b.lo = v.lo, b.hi = v.hi;
      b.cos_theta_o = -1.f;
      b.cos_theta_e = 0.f;
      b.phi = v.power / (4.f * kPi);
      return b;
    }
    default:
      return b;  // at infinity: no bounds (phi stays 0)
  }
}

namespace {

// A constant environment (no image, no portal) is left to BSDF sampling: its radiance
// is the same from every direction, so sampling the BSDF (the cosine, for a
// diffuse surface) is never worse than sampling the sphere uniformly, and a
// light sample spent on it is one not spent on the lights that need them.
// pbrt-v4's path tracer skips it too (an "incomplete" light pdf), but still
// lets its sampler choose it and then wastes that sample.
bool sampled_by_next_event(const LightPools& lights, uint32_t light) {
  const LightRef r = lights.all[light];
  return !(r.kind == LightKind::Infinite && lights.infinite[r.index].image < 0 && lights.infinite[r.index].portal < 0);
}

}  // namespace

LightSampler::LightSampler(const LightPools& lights, const ShapePools& shapes, const TexturePools& tex,
                           LightSamplerKind kind)
    : lights_(lights), kind_(kind) {
  const auto start = std::chrono::steady_clock::now();
  const size_t n = lights.all.size();
  for (uint32_t i = 0; i < n; ++i)
    if (sampled_by_next_event(lights, i)) eligible_.push_back(i);
  if (kind_ == LightSamplerKind::Power) {
    std::vector<float> power(n, 0.f);  // constant environments keep 0
    for (uint32_t i : eligible_) power[i] = light_power(lights, lights.all[i], tex);
    power_ = Distribution1D(std::move(power));
  }
  if (kind_ != LightSamplerKind::Bvh || eligible_.empty()) return;
  is_infinite_.assign(n, 0);
  std::vector<uint32_t> finite;
  for (uint32_t i : eligible_) {
    const LightKind k = lights.all[i].kind;
    if (k == LightKind::Distant || k == LightKind::Infinite) {
      infinite_.push_back(i);
      is_infinite_[i] = 1;
    } else {
      finite.push_back(i);
    }
  }
  std::vector<LightBounds> bounds(finite.size());
  tbb::parallel_for(size_t(0), finite.size(), [&](size_t i) { bounds[i] = light_bounds(lights, shapes, tex, finite[i]); });
  bvh_ = LightBvh(std::move(bounds), std::move(finite), n);
  if (!infinite_.empty()) p_infinite_ = float(infinite_.size()) / float(infinite_.size() + (bvh_.empty() ? 0 : 1));
  build_seconds_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

bool LightSampler::sample(const Vec3& p, const Vec3& n, float u, uint32_t* light, float* pmf,
                          float* u_remapped) const {
  const size_t count = eligible_.size();
  if (count == 0) return false;
  float rest = 0.5f;
  if (!u_remapped) u_remapped = &rest;
  switch (kind_) {
    case LightSamplerKind::Power: {
      size_t i = power_.sample_discrete(u, pmf, u_remapped);
      *light = uint32_t(i);
      return *pmf > 0.f;
    }
    case LightSamplerKind::Uniform: {
      const size_t i = std::min(size_t(u * float(count)), count - 1);
      *light = eligible_[i];
      *pmf = 1.f / float(count);
      *u_remapped = std::clamp(u * float(count) - float(i), 0.f, kOneMinusEpsilon);
      return true;
    }
    case LightSamplerKind::Bvh:
      break;
  }
  if (u < p_infinite_) {
    const size_t k = infinite_.size();
    const float x = u / p_infinite_ * float(k);
    const size_t i = std::min(size_t(x), k - 1);
    *light = infinite_[i];
    *pmf = p_infinite_ / float(k);
    *u_remapped = std::clamp(x - float(i), 0.f, kOneMinusEpsilon);
    return true;
  }
  u = std::min((u - p_infinite_) / (1.f - p_infinite_), kOneMinusEpsilon);
  if (!bvh_.sample(p, n, u, light, pmf, u_remapped)) return false;
  *pmf *= 1.f - p_infinite_;
  return true;
}

float LightSampler::pmf(const Vec3& p, const Vec3& n, uint32_t light) const {
  switch (kind_) {
    case LightSamplerKind::Power: return eligible_.empty() ? 0.f : power_.discrete_pmf(light);
    case LightSamplerKind::Uniform:
      return sampled_by_next_event(lights_, light) ? 1.f / float(eligible_.size()) : 0.f;
    case LightSamplerKind::Bvh: break;
  }
  if (light >= is_infinite_.size()) return 0.f;  // no lights at all
  if (is_infinite_[light]) return p_infinite_ / float(infinite_.size());
  return bvh_.pmf(p, n, light) * (1.f - p_infinite_);
}

}  // namespace lantern
