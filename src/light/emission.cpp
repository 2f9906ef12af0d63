#include "light/emission.h"
#include "light/light_choice.h"
#include "light/light_sampler.h"

#include "math/sampling.h"
#include "geometry/surface.h"

namespace lantern {

namespace {

float area_dir_pdf(const AreaLight& a, const Vec3& n, const Vec3& w) {
  float c = glm::dot(n, w);
  if (!a.two_sided && c <= 0.f) return 0.f;
  return cosine_hemisphere_pdf(std::fabs(c)) * (a.two_sided ? 0.5f : 1.f);
}

float spot_falloff(const SpotLight& s, const Vec3& w) {
  return smooth_cone_weight(glm::dot(w, s.frame.n), s.cos_falloff_start, s.cos_falloff_end);
}

float disk_pdf(const LightPools& L) { return 1.f / (kPi * sqr(L.scene_radius)); }

// A ray from a light at infinity: it starts on a disk facing the scene
// (radius of the scene's bounding sphere), outside the scene.
void start_on_disk(const LightPools& L, Vec2 u, EmissionSample* es) {
  Frame f = Frame::from_z(es->d);
  Vec2 disk = sample_uniform_disk_concentric(u);
  es->p = L.scene_center + L.scene_radius * (disk.x * f.s + disk.y * f.t - es->d);
  es->pdf_pos *= disk_pdf(L);
  es->error_scale = max_abs_component(es->p);
  es->infinite = true;
}

}  // namespace

std::optional<EmissionSample> sample_le(const LightPools& L, const ShapePools& shapes, const TexturePools& tex,
                                        const Distribution1D& choice, LazyNumber u_select, Vec2 u_pos, Vec2 u_dir,
                                        const SampledWavelengths& l, float u_volume) {
  if (L.all.empty()) return std::nullopt;
  float pmf, rest;
  size_t i = choice.sample_discrete(u_pos.x, &pmf, &rest);
  if (pmf == 0.f) return std::nullopt;
  u_pos.x = light_point_coordinate(rest, pmf, u_select);
  const LightRef r = L.all[i];
  EmissionSample es;
  es.light = uint32_t(i);
  es.pdf_pos = pmf;
  es.pdf_dir = 1.f;
  switch (r.kind) {
    case LightKind::Volume: {  // isotropic, as pbrt-v4's media emit
      float pdf_volume;
      es.p = sample_volume_point(L.volume[r.index], Vec3(u_volume, u_pos.x, u_pos.y), &pdf_volume);
      es.pdf_pos *= pdf_volume;
      es.d = sample_uniform_sphere(u_dir);
      es.pdf_dir = uniform_sphere_pdf();
      es.Le = Spectrum(1.f);
      es.error_scale = max_abs_component(es.p);
      es.volume = true;
      break;
    }
    case LightKind::Area: {
      const AreaLight& a = L.area[r.index];
      const SurfacePoint sp = sample_area_point(shapes, a, u_pos);
      // Cosine-weighted about the normal; a two-sided light picks a side.
      bool back = false;
      if (a.two_sided) {
        back = u_dir.x < 0.5f;
        u_dir.x = back ? 2.f * u_dir.x : 2.f * u_dir.x - 1.f;
      }
      Vec3 wl = sample_cosine_hemisphere(u_dir);
      Frame f = Frame::from_z(back ? -sp.ng : sp.ng);
      es.p = sp.p;
      es.n = sp.ng;
      es.uv = sp.uv;
      es.d = f.from_local(wl);
      es.pdf_pos *= area_point_density(shapes, a, sp.p, sp.ng);
      es.pdf_dir = area_dir_pdf(a, sp.ng, es.d);
      es.Le = area_light_Le(a, tex, sp.ng, sp.uv, es.d, l);
      es.error_scale = sp.error_scale;
      break;
    }
    case LightKind::Point: {
      const PointLight& pl = L.point[r.index];
      es.p = pl.p;
      if (pl.profile < 0) {
        es.d = sample_uniform_sphere(u_dir);
        es.pdf_dir = uniform_sphere_pdf();
      } else if (!sample_profile(L.profiles[size_t(pl.profile)], u_dir, &es.d, &es.pdf_dir)) {
        return std::nullopt;
      }
      es.Le = light_spectrum(point_intensity(L, tex, pl, es.d), pl.spectrum, tex, l);
      es.error_scale = max_abs_component(pl.p);
      es.delta_pos = true;
      break;
    }
    case LightKind::Spot: {
      const SpotLight& s = L.spot[r.index];
      es.p = s.p;
      // (directions by the falloff: the intensity over the density is constant)
      const Vec3 local = sample_smooth_cone(u_dir, s.cos_falloff_start, s.cos_falloff_end);
      es.d = s.frame.from_local(local);
      es.pdf_dir = smooth_cone_pdf(local.z, s.cos_falloff_start, s.cos_falloff_end);
      es.Le = light_spectrum(s.I, s.spectrum, tex, l) * spot_falloff(s, es.d);
      es.error_scale = max_abs_component(s.p);
      es.delta_pos = true;
      break;
    }
    case LightKind::Distant: {
      const DistantLight& dl = L.distant[r.index];
      es.d = -dl.w;
      es.Le = light_spectrum(dl.L, dl.spectrum, tex, l);
      es.delta_dir = true;
      start_on_disk(L, u_pos, &es);
      break;
    }
    case LightKind::Infinite: {
      const InfiniteLight& e = L.infinite[r.index];
      if (e.portal >= 0) {  // any direction of the map; the first hit applies the window
        Vec3 w;
        RGB c;
        if (!sample_portal_emission(L.portals[size_t(e.portal)], u_dir, &w, &es.pdf_dir, &c)) return std::nullopt;
        es.Le = illuminant_spectrum(c, l);
        es.d = -w;
        start_on_disk(L, u_pos, &es);
        break;
      }
      // The direction is drawn exactly as next-event estimation draws it.
      auto ls = sample_light_from(L, shapes, tex, uint32_t(i), Vec3(0.f), u_dir, l);
      if (!ls || ls->pdf == 0.f) return std::nullopt;
      es.d = -ls->wi;
      es.Le = ls->L;
      es.pdf_dir = ls->pdf;
      start_on_disk(L, u_pos, &es);
      break;
    }
  }
  if (!(es.pdf_pos > 0.f) || !(es.pdf_dir > 0.f) || is_black(es.Le)) return std::nullopt;
  return es;
}

bool redirect_area_emission(const LightPools& L, const TexturePools& tex, EmissionSample& es, const Vec3& d,
                            const SampledWavelengths& l) {
  if (es.volume || es.infinite || es.light >= L.all.size() || L.all[es.light].kind != LightKind::Area) return false;
  const AreaLight& a = L.area[L.all[es.light].index];
  es.d = d;
  es.pdf_dir = area_dir_pdf(a, es.n, d);
  es.Le = area_light_Le(a, tex, es.n, es.uv, d, l);
  return true;
}

float area_emission_pdf(const LightPools& L, const ShapePools& shapes, const Distribution1D& choice,
                        uint32_t area_index, const Vec3& p, const Vec3& n, const Vec3& w) {
  const AreaLight& a = L.area[area_index];
  return choice.discrete_pmf(L.area_to_all[area_index]) * area_point_density(shapes, a, p, n) * area_dir_pdf(a, n, w);
}

float infinite_emission_pdf(const LightPools& L, const TexturePools& tex, const Distribution1D& choice, uint32_t index,
                            const Vec3& w_to_light) {
  return choice.discrete_pmf(L.infinite_to_all[index]) * infinite_light_emission_dir_pdf(L, tex, index, w_to_light) *
         disk_pdf(L);
}

float emission_pdf(const LightPools& L, const ShapePools& shapes, const TexturePools& tex, const Distribution1D& choice,
                   uint32_t light, const Vec3& p, const Vec3& n, const Vec3& w) {
  const LightRef r = L.all[light];
  float pmf = choice.discrete_pmf(light);
  switch (r.kind) {
    case LightKind::Area:
      return area_emission_pdf(L, shapes, choice, r.index, p, n, w);
    case LightKind::Point: {
      const PointLight& pl = L.point[r.index];
      return pmf * (pl.profile < 0 ? uniform_sphere_pdf() : profile_pdf(L.profiles[size_t(pl.profile)], w));
    }
    case LightKind::Spot: {
      const SpotLight& s = L.spot[r.index];
      return pmf * smooth_cone_pdf(glm::dot(w, s.frame.n), s.cos_falloff_start, s.cos_falloff_end);
    }
    case LightKind::Distant:
      return pmf * disk_pdf(L);
    case LightKind::Volume:
      return pmf * volume_point_density(L.volume[r.index], p) * uniform_sphere_pdf();
    case LightKind::Infinite: {
      auto pdf = infinite_light_emission_dir_pdf(L, tex, r.index, -w);
      return pmf * pdf * disk_pdf(L);
    }
  }
  return 0.f;
}

Spectrum emitted(const LightPools& L, const TexturePools& tex, uint32_t light, const Vec3& n, Vec2 uv, const Vec3& w,
                 const SampledWavelengths& l) {
  const LightRef r = L.all[light];
  switch (r.kind) {
    case LightKind::Area:
      return area_light_Le(L.area[r.index], tex, n, uv, w, l);
    case LightKind::Point:
      return light_spectrum(point_intensity(L, tex, L.point[r.index], w), L.point[r.index].spectrum, tex, l);
    case LightKind::Spot:
      return light_spectrum(L.spot[r.index].I, L.spot[r.index].spectrum, tex, l) * spot_falloff(L.spot[r.index], w);
    default:
      return Spectrum(0.f);
  }
}

float area_light_direct_pdf_area(const LightPools& L, const ShapePools& shapes, const LightSampler& sampler,
                                 uint32_t area_index, const Vec3& p, const Vec3& n, const Vec3& p_light,
                                 const Vec3& n_light) {
  Vec3 d = p_light - p;
  float dist2 = glm::dot(d, d);
  if (!(dist2 > 0.f)) return 0.f;
  float cos_l = std::fabs(glm::dot(n_light, d)) / std::sqrt(dist2);
  return area_light_pdf(L, shapes, sampler, area_index, p, n, p_light, n_light) * cos_l / dist2;
}

float emission_direct_pdf_fixed(const LightPools& L, const LightSampler& sampler, const EmissionSample& es) {
  const LightRef& ref = L.all[es.light];
  const float nee_pmf = sampler.pmf_infinite(es.light);  // used for lights at infinity only
  // A portal light's next-event density depends on the point lit (its window) too.
  const bool portal = ref.kind == LightKind::Infinite && L.infinite[ref.index].portal >= 0;
  return portal                            ? -1.f
         : ref.kind == LightKind::Infinite ? nee_pmf * es.pdf_dir
         : ref.kind == LightKind::Distant  ? nee_pmf
                                           : -1.f;
}

float emission_direct_pdf_from(const LightPools& L, const ShapePools& shapes, const TexturePools& tex,
                               const LightSampler& sampler, uint32_t light, const Vec3& n_light, const Vec3& p,
                               const Vec3& ns, const Vec3& p_light) {
  const LightRef& ref = L.all[light];
  switch (ref.kind) {
    case LightKind::Infinite:  // a portal light, seen through its window from p
      return sampler.pmf_infinite(light) * infinite_light_pdf(L, tex, ref.index, p, glm::normalize(p_light - p));
    case LightKind::Volume: return sampler.pmf(p, ns, light) * volume_light_density(L, light, p_light);  // per unit volume
    case LightKind::Area: return area_light_direct_pdf_area(L, shapes, sampler, ref.index, p, ns, p_light, n_light);
    default: return sampler.pmf(p, ns, light);  // point and spot lights: a delta position
  }
}

}  // namespace lantern
