#include "light/lights.h"

#include "math/spherical_triangle.h"

#include "light/light_choice.h"
#include "light/light_sampler.h"
#include "math/sampling.h"
#include "geometry/surface.h"
#include "texture/texture.h"

namespace lantern {

static Vec3 latlong_to_dir(Vec2 uv, float* sin_theta) {
  float theta = uv.y * kPi, phi = uv.x * 2.f * kPi;
  *sin_theta = std::sin(theta);
  return Vec3(*sin_theta * std::cos(phi), *sin_theta * std::sin(phi), std::cos(theta));
}
static Vec2 dir_to_latlong(const Vec3& w) {
  float theta = std::acos(glm::clamp(w.z, -1.f, 1.f));
  float phi = std::atan2(w.y, w.x);
  if (phi < 0.f) phi += 2.f * kPi;
  return Vec2(glm::clamp(phi * kInv2Pi, 0.f, kOneMinusEpsilon), glm::clamp(theta * kInvPi, 0.f, kOneMinusEpsilon));
}

static RGB env_lookup(const InfiniteLight& l, const TexturePools& tex, Vec2 uv) {
  const TextureImage& img = tex.images[size_t(l.image)];
  int x = glm::clamp(int(uv.x * float(img.width)), 0, img.width - 1);
  int y = glm::clamp(int(uv.y * float(img.height)), 0, img.height - 1);
  return l.scale * img.texels[size_t(y) * size_t(img.width) + size_t(x)];
}

float light_power(const LightPools& L, const LightRef& r, const TexturePools& tex) {
  auto avg = [](const RGB& c) { return (c[0] + c[1] + c[2]) / 3.f; };
  float disk = kPi * sqr(L.scene_radius);
  switch (r.kind) {
    case LightKind::Area: {
      const AreaLight& a = L.area[r.index];
      float mean = a.image < 0 ? 1.f : tex.image_mean(a.image);
      return avg(a.L) * mean * a.area * kPi * (a.two_sided ? 2.f : 1.f);
    }
    case LightKind::Point: return 4.f * kPi * point_mean_intensity(L, L.point[r.index]);
    case LightKind::Spot: {
      const SpotLight& s = L.spot[r.index];
      return avg(s.I) * smooth_cone_mass(s.cos_falloff_start, s.cos_falloff_end);
    }
    case LightKind::Distant: return avg(L.distant[r.index].L) * disk;
    case LightKind::Volume: return L.volume[r.index].power;
    case LightKind::Infinite: {
      const InfiniteLight& e = L.infinite[r.index];
      if (e.portal >= 0) return portal_power(L.portals[size_t(e.portal)]);
      float mean = avg(e.scale);
      if (e.image >= 0) {
        const TextureImage& img = tex.images[size_t(e.image)];
        double s = 0.0;
        for (const RGB& c : img.texels) s += double(avg(c));
        mean *= float(s / double(img.texels.size()));
      }
      return 4.f * kPi * disk * mean;
    }
  }
  return 0.f;
}

void finalize_lights(LightPools& L, const ShapePools& shapes, const TexturePools& tex, Vec3 center, float radius) {
  L.scene_center = center;
  L.scene_radius = radius;
  L.all.clear();
  L.area_to_all.resize(L.area.size());
  L.infinite_to_all.resize(L.infinite.size());
  for (uint32_t i = 0; i < L.area.size(); ++i) {
    L.area_to_all[i] = uint32_t(L.all.size());
    L.all.push_back({LightKind::Area, i});
  }
  for (uint32_t i = 0; i < L.point.size(); ++i) L.all.push_back({LightKind::Point, i});
  for (IntensityProfile& p : L.profiles) finalize_profile(p, tex);
  for (uint32_t i = 0; i < L.spot.size(); ++i) L.all.push_back({LightKind::Spot, i});
  for (uint32_t i = 0; i < L.distant.size(); ++i) L.all.push_back({LightKind::Distant, i});
  L.volume_to_all.resize(L.volume.size());
  for (uint32_t i = 0; i < L.volume.size(); ++i) {
    L.volume_to_all[i] = uint32_t(L.all.size());
    L.all.push_back({LightKind::Volume, i});
  }
  for (uint32_t i = 0; i < L.infinite.size(); ++i) {
    L.infinite_to_all[i] = uint32_t(L.all.size());
    L.all.push_back({LightKind::Infinite, i});
    InfiniteLight& e = L.infinite[i];
    if (e.image < 0 || e.portal >= 0) continue;
    const TextureImage& img = tex.images[size_t(e.image)];
    std::vector<float> w(img.texels.size());
    for (int y = 0; y < img.height; ++y) {
      float sin_theta = e.equal_area ? 1.f : std::sin(kPi * (float(y) + 0.5f) / float(img.height));
      for (int x = 0; x < img.width; ++x) {
        const RGB& c = img.texels[size_t(y) * size_t(img.width) + size_t(x)];
        w[size_t(y) * size_t(img.width) + size_t(x)] = (c[0] + c[1] + c[2]) * sin_theta;
      }
    }
    e.distribution = Distribution2D(w, img.width, img.height);
  }
  std::vector<float> power(L.all.size());
  for (size_t i = 0; i < L.all.size(); ++i) power[i] = light_power(L, L.all[i], tex);
  L.selection = Distribution1D(std::move(power));
}

// sin^2 of the half angle the sphere subtends from p, or 1 when p is inside
// or on the sphere. Points on the surface (a sphere lighting itself from
// within) must count as inside whatever the rounding of p, so the test
// has a relative margin; sampling and pdf share it and stay consistent.
static float sphere_cone_sin2_max(const Sphere& s, const Vec3& p) {
  float s2 = sqr(s.radius) / glm::dot(p - s.center, p - s.center);
  return s2 >= 1.f - 1e-3f ? 1.f : s2;
}

SurfacePoint sample_area_point(const ShapePools& shapes, const AreaLight& a, Vec2 u) {
  const Geometry& g = shapes.geometries[a.geometry];
  switch (g.kind) {
    case ShapeKind::Mesh: {
      Vec2 b = sample_uniform_triangle(u);
      return triangle_point(shapes.meshes[g.index], a.primitive, b.y, 1.f - b.x - b.y);
    }
    case ShapeKind::Sphere: return sphere_point_at_normal(shapes.spheres[g.index], sample_uniform_sphere(u));
    case ShapeKind::Quadric: {
      const Quadric& q = shapes.quadrics[g.index];
      return quadric_point(q, quadric_sample_uv(q, u));
    }
    case ShapeKind::Bilinear: {
      const BilinearPatchSet& s = shapes.patches[g.index];
      return bilinear_point(s, a.primitive, sample_bilinear_patch(patch_corners(s, a.primitive), u));
    }
    case ShapeKind::Curve: break;  // curves do not emit (refused at load)
  }
  return {};
}

float area_point_density(const ShapePools& shapes, const AreaLight& a, const Vec3& p, const Vec3& n) {
  const Geometry& g = shapes.geometries[a.geometry];
  if (g.kind == ShapeKind::Quadric) return quadric_area_density(shapes.quadrics[g.index], n);
  if (g.kind == ShapeKind::Bilinear) {
    const PatchCorners c = patch_corners(shapes.patches[g.index], a.primitive);
    return bilinear_area_density(c, bilinear_uv_of(c, p));
  }
  return 1.f / a.area;
}

// The directions triangle light a subtends from p, if next-event
// estimation samples them (math/spherical_triangle.h); a zero solid angle
// otherwise, and for other shapes.
static SphericalTriangle light_spherical_triangle(const ShapePools& shapes, const AreaLight& a, const Vec3& p) {
  const Geometry& g = shapes.geometries[a.geometry];
  if (g.kind != ShapeKind::Mesh) return {};
  const TriangleMesh& m = shapes.meshes[g.index];
  const glm::uvec3 t = m.triangle(a.primitive);
  const Vec3 &p0 = m.positions[t.x], &p1 = m.positions[t.y], &p2 = m.positions[t.z];
  // Its solid angle, roughly (area times cosine over the squared distance
  // of the centroid), decides whether the exact one is worth computing.
  const Vec3 d = (p0 + p1 + p2) / 3.f - p;
  const float d2 = glm::dot(d, d);
  const float approx = 0.5f * std::fabs(glm::dot(glm::cross(p1 - p0, p2 - p0), d)) / (d2 * std::sqrt(d2));
  if (!(approx >= kSphericalSamplingFrom)) return {};
  return spherical_triangle(p, p0, p1, p2);
}

// The point where the ray from p in direction w meets the plane of light
// a's triangle (Moller & Trumbore 1997), kept inside the triangle.
static std::optional<SurfacePoint> triangle_point_along(const ShapePools& shapes, const AreaLight& a, const Vec3& p,
                                                       const Vec3& w) {
  const TriangleMesh& m = shapes.meshes[shapes.geometries[a.geometry].index];
  const glm::uvec3 t = m.triangle(a.primitive);
  const glm::dvec3 p0(m.positions[t.x]), e1 = glm::dvec3(m.positions[t.y]) - p0, e2 = glm::dvec3(m.positions[t.z]) - p0;
  const glm::dvec3 dir(w), pv = glm::cross(dir, e2);
  const double det = glm::dot(e1, pv);
  if (!(std::fabs(det) > 0.0)) return std::nullopt;
  const glm::dvec3 tv = glm::dvec3(p) - p0, qv = glm::cross(tv, e1);
  double b1 = std::max(glm::dot(tv, pv) / det, 0.0), b2 = std::max(glm::dot(dir, qv) / det, 0.0);
  if (!std::isfinite(b1 + b2)) return std::nullopt;
  if (b1 + b2 > 1.0) {
    const double sum = b1 + b2;
    b1 /= sum;
    b2 /= sum;
  }
  return triangle_point(m, a.primitive, float(b1), float(b2));
}

// The samplers below fill a default LightSample in place and say whether
// there is a sample: built where the caller keeps it, it is never copied
// (copies of the optional, written field by field and read back whole,
// were a tenth of the path tracer's time).
static bool sample_area(const ShapePools& shapes, const TexturePools& tex, const AreaLight& a, const Vec3& p,
                        const Vec3& n, Vec2 u,
                        const SampledWavelengths& l, LightSample& ls) {
  const Geometry& g = shapes.geometries[a.geometry];
  SurfacePoint sp;
  float pdf;
  const float sin2_max = g.kind == ShapeKind::Sphere ? sphere_cone_sin2_max(shapes.spheres[g.index], p) : 1.f;
  const SphericalTriangle st = light_spherical_triangle(shapes, a, p);
  if (samples_spherical(st)) {  // over the directions the triangle subtends, warped towards n
    float warp = 1.f;
    if (n != Vec3(0.f)) {
      float w[4];
      cosine_warp_weights(st, n, w);
      u = sample_bilinear(u, w);
      warp = bilinear_pdf(u, w);
    }
    const std::optional<SurfacePoint> hit = triangle_point_along(shapes, a, p, sample_spherical_triangle(st, u));
    if (!hit) return false;
    sp = *hit;
    pdf = float(double(warp) / st.solid_angle);
  } else if (sin2_max >= 1.f) {  // by area (a sphere: from inside), converted to solid angle
    sp = sample_area_point(shapes, a, u);
    Vec3 d = sp.p - p;
    float dist2 = glm::dot(d, d);
    float cos_l = std::fabs(glm::dot(sp.ng, d)) / std::sqrt(dist2);
    pdf = dist2 * area_point_density(shapes, a, sp.p, sp.ng) / cos_l;
  } else {
    const Sphere& s = shapes.spheres[g.index];
    // Uniform over the cone of directions the sphere subtends, with the
    // point computed by trigonometry rather than a ray-sphere test.
    float sin_max = std::sqrt(sin2_max), cos_max = safe_sqrt(1.f - sin2_max);
    float one_minus_cos_max = 1.f - cos_max;
    float cos_t = (cos_max - 1.f) * u.x + 1.f;
    float sin2_t = 1.f - cos_t * cos_t;
    if (sin2_max < 0.00068523f) {  // sin^2(1.5 deg): use a Taylor expansion
      sin2_t = sin2_max * u.x;
      cos_t = std::sqrt(1.f - sin2_t);
      one_minus_cos_max = sin2_max / 2.f;
    }
    float cos_alpha = sin2_t / sin_max + cos_t * safe_sqrt(1.f - sin2_t / sin2_max);
    float sin_alpha = safe_sqrt(1.f - cos_alpha * cos_alpha);
    float phi = u.y * 2.f * kPi;
    Vec3 w(sin_alpha * std::cos(phi), sin_alpha * std::sin(phi), cos_alpha);
    Frame f = Frame::from_z(glm::normalize(s.center - p));
    Vec3 n = f.from_local(-w);
    sp = sphere_point_at_normal(s, n);
    pdf = 1.f / (2.f * kPi * one_minus_cos_max);
  }
  Vec3 d = sp.p - p;
  float dist2 = glm::dot(d, d);
  if (!(dist2 > 0.f) || !std::isfinite(pdf) || pdf <= 0.f) return false;
  ls.wi = d / std::sqrt(dist2);
  ls.L = area_light_Le(a, tex, sp.ng, sp.uv, -ls.wi, l);
  ls.pdf = pdf;
  ls.p_light = sp.p;
  ls.n_light = sp.ng;
  ls.error_scale = sp.error_scale;
  return true;
}

static bool sample_light_into(const LightPools& L, const ShapePools& shapes, const TexturePools& tex, uint32_t i,
                              const Vec3& p, const Vec3& n, Vec2 u, float u_volume, const SampledWavelengths& l,
                              LightSample& ls) {
  const LightRef r = L.all[i];
  switch (r.kind) {
    case LightKind::Volume: {
      float pdf_volume;
      const Vec3 x = sample_volume_point(L.volume[r.index], Vec3(u_volume, u.x, u.y), &pdf_volume);
      const Vec3 d = x - p;
      const float dist2 = glm::dot(d, d);
      if (!(dist2 > 0.f) || !(pdf_volume > 0.f)) return false;
      ls.L = Spectrum(1.f);
      ls.wi = d / std::sqrt(dist2);
      ls.pdf = pdf_volume * dist2;
      ls.p_light = x;
      ls.volume = true;
      break;
    }
    case LightKind::Area:
      if (!sample_area(shapes, tex, L.area[r.index], p, n, u, l, ls)) return false;
      break;
    case LightKind::Point: {
      const PointLight& pl = L.point[r.index];
      Vec3 d = pl.p - p;
      float dist2 = glm::dot(d, d);
      if (!(dist2 > 0.f)) return false;
      const Vec3 wi = d / std::sqrt(dist2);
      ls = LightSample{light_spectrum(point_intensity(L, tex, pl, -wi), pl.spectrum, tex, l) / dist2, wi, 1.f, pl.p, Vec3(0.f), max_abs_component(pl.p), true, false};
      break;
    }
    case LightKind::Spot: {
      const SpotLight& s = L.spot[r.index];
      Vec3 d = s.p - p;
      float dist2 = glm::dot(d, d);
      if (!(dist2 > 0.f)) return false;
      Vec3 wi = d / std::sqrt(dist2);
      float cos_t = glm::dot(-wi, s.frame.n);
      float falloff = smooth_cone_weight(cos_t, s.cos_falloff_start, s.cos_falloff_end);
      ls = LightSample{light_spectrum(s.I, s.spectrum, tex, l) * falloff / dist2, wi, 1.f, s.p, Vec3(0.f), max_abs_component(s.p), true, false};
      break;
    }
    case LightKind::Distant: {
      const DistantLight& dl = L.distant[r.index];
      ls = LightSample{light_spectrum(dl.L, dl.spectrum, tex, l), dl.w, 1.f, Vec3(0.f), Vec3(0.f), 0.f, true, true};
      break;
    }
    case LightKind::Infinite: {
      const InfiniteLight& e = L.infinite[r.index];
      LightSample& s = ls;
      s.infinite = true;
      if (e.portal >= 0) {
        RGB c;
        if (!sample_portal(L.portals[size_t(e.portal)], p, u, &s.wi, &s.pdf, &c)) return false;
        s.L = illuminant_spectrum(c, l);
      } else if (e.image < 0) {
        s.wi = sample_uniform_sphere(u);
        s.pdf = uniform_sphere_pdf();
        s.L = light_spectrum(e.scale, e.spectrum, tex, l);
      } else {
        float pdf_uv;
        Vec2 uv = e.distribution.sample_continuous(u, &pdf_uv);
        if (pdf_uv == 0.f) return false;
        Vec3 wl;
        if (e.equal_area) {
          wl = equal_area_square_to_sphere(uv);
          s.pdf = pdf_uv / (4.f * kPi);
        } else {
          float sin_theta;
          wl = latlong_to_dir(uv, &sin_theta);
          if (sin_theta <= 0.f) return false;
          s.pdf = pdf_uv / (2.f * kPi * kPi * sin_theta);
        }
        s.wi = glm::normalize(e.world_from_light * wl);
        s.L = illuminant_spectrum(env_lookup(e, tex, uv), l);
      }
      break;
    }
  }
  if (ls.pdf == 0.f) return false;
  ls.light = i;
  return true;
}

std::optional<LightSample> sample_light_from(const LightPools& L, const ShapePools& shapes, const TexturePools& tex,
                                             uint32_t i, const Vec3& p, Vec2 u, const SampledWavelengths& l,
                                             float u_volume) {
  std::optional<LightSample> ls(std::in_place);
  if (!sample_light_into(L, shapes, tex, i, p, Vec3(0.f), u, u_volume, l, *ls)) ls.reset();
  return ls;
}

std::optional<LightSample> sample_light(const LightPools& L, const ShapePools& shapes, const TexturePools& tex,
                                        const LightSampler& sampler, const Vec3& p, const Vec3& n, LazyNumber u_select,
                                        Vec2 u, const SampledWavelengths& l, float u_volume) {
  std::optional<LightSample> ls;
  uint32_t i;
  float pmf, rest;
  if (sampler.sample(p, n, u.x, &i, &pmf, &rest) && pmf != 0.f) {
    u.x = light_point_coordinate(rest, pmf, u_select);
    ls.emplace();
    if (sample_light_into(L, shapes, tex, i, p, n, u, u_volume, l, *ls)) ls->pdf *= pmf;
    else ls.reset();
  }
  return ls;
}

float area_light_pdf(const LightPools& L, const ShapePools& shapes, const LightSampler& sampler,
                     uint32_t area_index, const Vec3& p, const Vec3& n, const Vec3& p_light, const Vec3& n_light) {
  const AreaLight& a = L.area[area_index];
  const float pmf = sampler.pmf(p, n, L.area_to_all[area_index]);
  if (pmf == 0.f) return 0.f;
  const Geometry& g = shapes.geometries[a.geometry];
  if (g.kind == ShapeKind::Mesh) {
    const SphericalTriangle st = light_spherical_triangle(shapes, a, p);
    if (samples_spherical(st)) {
      float warp = 1.f;
      if (n != Vec3(0.f)) {
        float w[4];
        cosine_warp_weights(st, n, w);
        warp = bilinear_pdf(invert_spherical_triangle(st, glm::normalize(p_light - p)), w);
      }
      return pmf * float(double(warp) / st.solid_angle);
    }
  }
  if (g.kind == ShapeKind::Sphere) {
    const Sphere& s = shapes.spheres[g.index];
    float sin2_max = sphere_cone_sin2_max(s, p);
    if (sin2_max < 1.f) {
      float one_minus_cos_max = sin2_max < 0.00068523f ? sin2_max / 2.f : 1.f - safe_sqrt(1.f - sin2_max);
      return pmf / (2.f * kPi * one_minus_cos_max);
    }
  }
  Vec3 d = p_light - p;
  float dist2 = glm::dot(d, d);
  float cos_l = std::fabs(glm::dot(n_light, d)) / std::sqrt(dist2);
  if (cos_l == 0.f || a.area == 0.f) return 0.f;
  return pmf * dist2 * area_point_density(shapes, a, p_light, n_light) / cos_l;
}

// One infinite light's radiance along w leaving p (a portal's depends on
// p), as colour.
static RGB infinite_light_rgb(const LightPools& L, const InfiniteLight& e, const TexturePools& tex, const Vec3& p,
                              const Vec3& w) {
  if (e.portal >= 0) return portal_Le(L.portals[size_t(e.portal)], p, w);
  if (e.image < 0) return e.scale;
  Vec3 wl = glm::normalize(e.light_from_world * w);
  return env_lookup(e, tex, e.equal_area ? equal_area_sphere_to_square(wl) : dir_to_latlong(wl));
}

Spectrum infinite_light_Le(const LightPools& L, const TexturePools& tex, uint32_t index, const Vec3& p, const Vec3& w,
                           const SampledWavelengths& l) {
  const InfiniteLight& e = L.infinite[index];
  const RGB c = infinite_light_rgb(L, e, tex, p, w);
  return l.is_rgb() ? illuminant_spectrum(c, l) : light_spectrum(c, e.spectrum, tex, l);
}

float infinite_light_emission_dir_pdf(const LightPools& L, const TexturePools& tex, uint32_t index, const Vec3& w) {
  const InfiniteLight& e = L.infinite[index];
  if (e.portal >= 0) return portal_emission_pdf(L.portals[size_t(e.portal)], w);
  return infinite_light_pdf(L, tex, index, Vec3(0.f), w);
}

float infinite_light_pdf(const LightPools& L, const TexturePools& tex, uint32_t index, const Vec3& p, const Vec3& w) {
  const InfiniteLight& e = L.infinite[index];
  if (e.portal >= 0) return portal_pdf(L.portals[size_t(e.portal)], p, w);
  if (e.image < 0) return uniform_sphere_pdf();
  Vec3 wl = glm::normalize(e.light_from_world * w);
  if (e.equal_area) return e.distribution.pdf(equal_area_sphere_to_square(wl)) / (4.f * kPi);
  Vec2 uv = dir_to_latlong(wl);
  float sin_theta = std::sin(uv.y * kPi);
  return sin_theta > 0.f ? e.distribution.pdf(uv) / (2.f * kPi * kPi * sin_theta) : 0.f;
}

float infinite_light_sampled_pdf(const LightPools& L, const TexturePools& tex, const LightSampler& sampler,
                                 uint32_t index, const Vec3& p, const Vec3& w) {
  return sampler.pmf_infinite(L.infinite_to_all[index]) * infinite_light_pdf(L, tex, index, p, w);
}

MediumHandle emission_medium(const LightPools& L, const ShapePools& shapes, uint32_t light, const Vec3& n,
                             const Vec3& d) {
  const LightRef& ref = L.all[light];
  switch (ref.kind) {
    case LightKind::Point: return L.point[ref.index].medium;
    case LightKind::Spot: return L.spot[ref.index].medium;
    case LightKind::Area: {
      const MediumInterface& mi = shapes.geometries[L.area[ref.index].geometry].media;
      return glm::dot(n, d) > 0.f ? mi.outside : mi.inside;
    }
    case LightKind::Volume: return L.volume[ref.index].medium;
    default: return {};  // lights at infinity emit into vacuum (docs/media.md)
  }
}

float light_sample_density_at_light(const LightPools& L, const LightSample& ls, float dist2) {
  switch (L.all[ls.light].kind) {
    case LightKind::Area: return ls.pdf * std::fabs(glm::dot(ls.n_light, ls.wi)) / dist2;
    case LightKind::Volume: return ls.pdf / dist2;
    default: return ls.pdf;
  }
}

bool reaches_through_portal(const LightPools& L, uint32_t light, const Vec3& p, const Vec3& w_to_light) {
  if (L.all[light].kind != LightKind::Infinite) return true;
  const InfiniteLight& e = L.infinite[L.all[light].index];
  return e.portal < 0 || through_portal(L.portals[size_t(e.portal)], p, w_to_light);
}

void complete_volume_sample(const LightPools& L, const MediumPools& media, Spectrum* Li, const Vec3& p,
                            uint32_t light, const SampledWavelengths& l, MediumHandle* m, Spectrum* sigma_t) {
  const VolumeLight& v = L.volume[L.all[light].index];
  Spectrum a, s;
  media.coefficients_at(v.medium, p, l, &a, &s);
  *Li *= a * media.Le(v.medium, p, l);
  *m = v.medium;
  *sigma_t = a + s;
}

float volume_light_density(const LightPools& L, int64_t light, const Vec3& p) {
  if (light < 0) return 0.f;
  return volume_point_density(L.volume[L.all[size_t(light)].index], p);
}

}  // namespace lantern
