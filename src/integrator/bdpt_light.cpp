// Light subpaths of the bidirectional tracer: emission, bounces, the stored
// light vertices, and the t = 1 strategies (light tracing onto the film).
#include "integrator/bdpt.h"
#include "integrator/bdpt_strategies.h"
#include "integrator/bdpt_wave.h"
#include "integrator/dispersion.h"
#include "integrator/hit.h"
#include "integrator/hit_material.h"
#include "integrator/shade.h"
#include "light/emission.h"
#include "integrator/shutter.h"
#include "integrator/wavelengths.h"
#include "sampler/dimensions.h"

namespace lantern {

namespace {
// Whether a light subpath goes on beyond the light (with probability q,
// the light subpath rate), decided by the first coordinate of the number
// its direction is drawn with, which is then rescaled to [0, 1) for that
// draw: at q = 1 the same directions. The light point is drawn for every
// camera sample, stratified with the image, for s = 1, t = 1.
bool beyond_light(float q, Vec2& u_dir) {
  if (q >= 1.f) return true;
  if (!(u_dir.x < q)) return false;
  u_dir.x = std::min(u_dir.x / q, kOneMinusEpsilon);
  return true;
}
}  // namespace

void Bdpt::start_light_subpaths(const WaveDesc& wave, BdptWave& w) const {
  const LightPools& lights = scene_.lights;
  w.rays.count = 0;
  w.shadow.rays.count = 0;
  w.vertices.clear();
  const bool emissive = scene_.media.any_emissive();
  const uint32_t maxdepth = uint32_t(settings_.maxdepth);
  std::vector<EmissionSample>& in_volume = w.volume_starts;  // waiting to learn which medium they are in
  in_volume.clear();
  // With merging, one set of wavelengths for the whole wave, its first
  // sample's (wavelengths.h).
  const PathSampler first = PathSampler::make(sampler_, wave.pixels[0], wave.first_sample);
  const SampledWavelengths wave_lambda =
      sample_wavelengths(settings_.spectral && settings_.merging, first, settings_.maxdepth, settings_.wavelengths);
  // So is its time: a light vertex merged with an eye vertex of another
  // sample must have been found in the same scene (docs/motion-blur.md).
  const float wave_time = sample_time(scene_, first, settings_.maxdepth);
  for (uint32_t slot = 0; slot < wave.size(); ++slot) {
    uint32_t pixel = wave.pixels[slot / wave.samples];
    PathSampler s = wave.chains ? PathSampler::metropolis(wave.chains + slot)
                                : PathSampler::make(sampler_, pixel, wave.first_sample + slot % wave.samples);
    const SampledWavelengths& lambda = w.lambda[slot] =
        settings_.merging ? wave_lambda : sample_wavelengths(settings_.spectral, s, settings_.maxdepth, settings_.wavelengths);
    w.time[slot] = settings_.merging ? wave_time : sample_time(scene_, s, settings_.maxdepth);
    // (its direction, like the rest of the subpath, keeps the pixel's own
    // layout: measured, the point gains from the image's stratification,
    // the direction does not)
    const PathSampler start = wave.chains || light_start_.pixel_bits == 0
                                  ? s  // the same layout as the pixel's: no second key
                                  : PathSampler::make(light_start_, pixel, wave.first_sample + slot % wave.samples);
    const LazyNumber u_select(start, dims::kLightSelect);
    Vec2 u_pos = start.get2d(dims::kLightPosition), u_dir = s.get2d(dims::kLightDirection);
    const float u_volume =
        emissive ? s.get1d(dims::volume_point(dims::vertex(maxdepth + 2), maxdepth, 0, true)) : 0.5f;
    w.pixel[slot] = pixel;
    w.L[slot] = Spectrum(0.f);
    w.light.dispersed[slot] = 0;
    w.sampler[slot] = s;
    w.origin.extra_depth[slot] = 0;
    const bool traced = beyond_light(settings_.light_subpath_rate, u_dir);
    auto es =
        sample_le(lights, scene_.shapes, scene_.textures, emission_choice_, u_select, u_pos, u_dir, lambda, u_volume);
    if (!es) continue;
    if (es->volume) {
      in_volume.push_back(*es);
      w.volume_slots.push_back(slot);
      continue;
    }
    float mix_pdf_dir = traced ? -1.f : 0.f;  // (0: not traced beyond the light)
    if (traced && guides_light()) guide_emission(w, slot, *es, u_select, u_pos, u_dir, &mix_pdf_dir);
    begin_light_subpath(w, slot, *es, !scene_.media.empty() ? emission_medium(lights, scene_.shapes, es->light, es->n, es->d) : MediumHandle{},
                        Spectrum(0.f), mix_pdf_dir);
  }
  if (!in_volume.empty()) start_volume_subpaths(w);
}

// Light subpaths that start at a point of an emissive medium: they count
// only if the point lies in that medium (locate_media, towards the camera,
// whose medium is known), and their paths have at most maxdepth segments
// (volume_lights.h), one fewer than the light's own depth count allows.
void Bdpt::start_volume_subpaths(BdptWave& w) const {
  if (settings_.maxdepth < 1) {  // such paths would have no segment
    w.volume_slots.clear();
    return;
  }
  std::vector<Vec3>& points = w.volume_points;
  points.clear();
  std::vector<float>& times = w.volume_times;
  times.clear();
  for (const EmissionSample& es : w.volume_starts) points.push_back(es.p);
  for (uint32_t slot : w.volume_slots) times.push_back(w.time[slot]);
  // (a moving camera is taken to stay in its medium: where it starts)
  locate_media(scene_, w.stream, points, times, camera_.position(), scene_.media.camera, w.volume_media, w.crossing);
  for (size_t k = 0; k < points.size(); ++k) {
    EmissionSample es = w.volume_starts[k];
    MediumHandle m;
    Spectrum sigma_t;
    complete_volume_sample(scene_.lights, scene_.media, &es.Le, es.p, es.light, w.lambda[w.volume_slots[k]], &m,
                           &sigma_t);
    if (w.volume_media[k] != m || is_black(es.Le)) continue;
    const uint32_t slot = w.volume_slots[k];
    // (the decision start_light_subpaths made: the same number, unscaled)
    Vec2 u_dir = w.sampler[slot].get2d(dims::kLightDirection);
    w.origin.extra_depth[slot] = 1;
    begin_light_subpath(w, slot, es, m, sigma_t, beyond_light(settings_.light_subpath_rate, u_dir) ? -1.f : 0.f);
  }
  w.volume_slots.clear();
}

// The light subpath of `slot` from emission sample es: its MIS start, the
// s = 1, t = 1 camera connection and its first ray. medium: where it
// starts (a volume light's; else the one towards es.d); sigma_origin: the
// extinction at a volume light's point.
void Bdpt::begin_light_subpath(BdptWave& w, uint32_t slot, const EmissionSample& es, MediumHandle medium,
                               const Spectrum& sigma_origin, float mix_pdf_dir) const {
  const LightPools& lights = scene_.lights;
  const bool on_surface = es.n != Vec3(0.f);
  const float cos_light = on_surface ? std::fabs(glm::dot(es.n, es.d)) : 1.f;
  const float emission_pdf_W = es.pdf_pos * es.pdf_dir;
  LightOriginPool& o = w.origin;
  o.light[slot] = es.light;
  o.n[slot] = es.n;
  o.emission_pdf_W[slot] = emission_pdf_W;
  o.cos_light[slot] = cos_light;
  o.delta[slot] = es.delta_pos || es.delta_dir;
  o.infinite[slot] = es.infinite;
  // Next-event estimation's density of this light point: for lights with a
  // position it depends on where it is seen from (the area density, and
  // the light sampler's choice), so it waits for the first hit (-1).
  o.direct_pdf_A[slot] = emission_direct_pdf_fixed(lights, light_sampler_, es);
  // (divided by the light subpath rate q: traced with probability q)
  const float inv_rate = 1.f / settings_.light_subpath_rate;
  Spectrum beta = mix_pdf_dir == 0.f ? Spectrum(0.f)
                  : es.Le * (cos_light / (mix_pdf_dir > 0.f ? es.pdf_pos * mix_pdf_dir : emission_pdf_W) * inv_rate);
  w.light.beta[slot] = beta;
  w.light.rr_scale[slot] = max_component(beta) > 0.f ? 1.f / max_component(beta) : 0.f;
  w.light.eta_scale[slot] = 1.f;
  w.light.prev_p[slot] = es.p;
  const bool media = !scene_.media.empty();
  if (media) {
    w.light.medium[slot] = medium;
    w.light.sigma_prev[slot] = sigma_origin;  // a volume light's point is reached by distance sampling
  }
  const Vec2 u_lens = lens_numbers(camera_, w.sampler[slot], dims::kLightStartLens);
  // s = 1, t = 1: the light's own point seen by the camera (bpm and ppm
  // see lights only through eye subpaths). Not for a point of zero size
  // (point, spot, goniometric and projection lights): its image is one
  // pixel's worth of energy that no camera ray can find, so the path tracer
  // and pbrt-v4 (whose bdpt skips s = 1, t = 1) leave it out, and so does
  // every integrator here.
  std::optional<Camera> moved;
  const Camera& camera = camera_at(camera_, w.time[slot], moved);
  if (!es.infinite && !es.delta_pos && settings_.connections) {
    if (auto cs = camera.sample_wi(es.p, u_lens)) {
      float cos_l = on_surface ? std::fabs(glm::dot(es.n, cs->wi)) : 1.f;
      Spectrum Le = es.volume ? es.Le : emitted(lights, scene_.textures, es.light, es.n, es.uv, cs->wi, w.lambda[slot]);
      if (!is_black(Le) && cos_l > 0.f) {
        Connection k;
        k.mis = mis_sums_light_origin(camera.pdf_area(-cs->wi, sqr(cs->dist), cos_l), es.pdf_pos, es.delta_pos, w.mis);
        k.mis.sigma_a = sigma_origin;  // a camera ray would end at a volume light's point by distance sampling
        k.unweighted = Le * (cos_l * cs->We / (cs->pdf * es.pdf_pos));
        k.p_raster = cs->p_raster;
        k.s = k.t = 1;
        k.o = on_surface ? offset_ray_origin(es.p, es.n, es.error_scale, cs->wi) : es.p;
        k.d = cs->p_lens - k.o;
        if (media) k.start = es.volume ? medium : emission_medium(lights, scene_.shapes, es.light, es.n, cs->wi);
        push_connection(w, slot, k);
      }
    }
  }
  if (settings_.maxdepth <= int(w.origin.extra_depth[slot]) || mix_pdf_dir == 0.f) return;
  Vec3 origin = on_surface ? offset_ray_origin(es.p, es.n, es.error_scale, es.d) : es.p;
  w.active[w.rays.count] = slot;
  w.rays.push(origin, es.d, 0.f, kInfinity, w.time[slot]);
}

// Finishes the MIS quantities of each hit and bins the hits by material.
void Bdpt::light_surface_stage(BdptWave& w) const {
  w.hits.clear_bins();
  const bool media = !scene_.media.empty();
  if (media) w.scattered.clear();
  for (uint32_t i = 0; i < w.rays.count; ++i) {
    uint32_t slot = w.active[i];
    w.hits.alive[i] = 0;
    if (media && w.ends.end[i] == SegmentEnd::Absorbed) {
      ++w.stats.light_ends[size_t(PathEnd::Absorbed)];
      continue;
    }
    if (media && w.ends.end[i] == SegmentEnd::Scatter) {
      light_medium_arrival(w, i);
      continue;
    }
    count_light_ray(w, slot);
    if (!w.rays.hit(i)) {
      ++w.stats.light_ends[size_t(PathEnd::Escaped)];
      continue;
    }
    ++w.stats.light_vertices;
    SurfacePoint sp = hit_point(scene_.shapes, w.rays, i);
    Vec3 d = glm::normalize(w.rays.direction(i));
    Vec3 prev = w.light.prev_p[slot];
    float dist2 = glm::dot(sp.p - prev, sp.p - prev);
    float cos_in = std::fabs(glm::dot(sp.ng, d));
    if (!(cos_in > 0.f) || !(dist2 > 0.f)) continue;
    // Light from a portal light arrives only through its window.
    if (w.depth == 1 && !reaches_through_portal(scene_.lights, w.origin.light[slot], sp.p, -d)) continue;
    Footprint fp;
    MaterialHandle material = hit_material(scene_, footprints_, w.rays, i, d, &sp, &fp);
    scatter_at(scene_.materials, material, settings_.spectral, w.light.beta[slot], w.light.dispersed[slot]);
    w.hits.store(i, sp, d, material, w.lambda[slot], footprints_.enabled() ? &fp : nullptr);
    MisState& m = w.light.mis[slot];
    if (w.depth == 1) {
      const LightOriginPool& o = w.origin;
      m = mis_light_start(first_hit_direct_pdf(o, slot, sp.p, w.hits.ns[i], prev), o.emission_pdf_W[slot],
                          o.cos_light[slot], o.delta[slot] != 0, w.mis);
      mis_after_hit(m, dist2, cos_in, !o.infinite[slot], w.mis);
    } else {
      mis_after_hit(m, dist2, cos_in, true, w.mis);
    }
    if (media) apply_segment(w, w.light, i);
  }
}

// A light subpath's vertex in a medium: its MIS quantities, as for a
// surface with no cosine (the light sampler sees it with no normal).
void Bdpt::light_medium_arrival(BdptWave& w, uint32_t i) const {
  const uint32_t slot = w.active[i];
  ++w.stats.light_vertices;
  count_light_ray(w, slot);
  const Vec3 p = w.ends.p[i], prev = w.light.prev_p[slot];
  const Vec3 d = glm::normalize(w.rays.direction(i));
  const float dist2 = glm::dot(p - prev, p - prev);
  if (!(dist2 > 0.f)) return;
  if (w.depth == 1 && !reaches_through_portal(scene_.lights, w.origin.light[slot], p, -d)) return;
  MisState& m = w.light.mis[slot];
  if (w.depth == 1) {
    const LightOriginPool& o = w.origin;
    m = mis_light_start(first_hit_direct_pdf(o, slot, p, Vec3(0.f), prev), o.emission_pdf_W[slot], o.cos_light[slot],
                        o.delta[slot] != 0, w.mis);
    mis_after_hit(m, dist2, 1.f, !o.infinite[slot], w.mis);
  } else {
    mis_after_hit(m, dist2, 1.f, true, w.mis);
  }
  apply_segment(w, w.light, i);
  w.scattered.push_back(i);
}

// The density with which next-event estimation from the light subpath's
// first hit (p, shading normal ns) would have chosen its light point: the
// light sampler's choice depends on that point.
float Bdpt::first_hit_direct_pdf(const LightOriginPool& o, uint32_t slot, const Vec3& p, const Vec3& ns,
                                 const Vec3& p_light) const {
  if (o.direct_pdf_A[slot] >= 0.f) return o.direct_pdf_A[slot];  // at infinity: independent of p
  return emission_direct_pdf_from(scene_.lights, scene_.shapes, scene_.textures, light_sampler_, o.light[slot], o.n[slot],
                                  p, ns, p_light);
}

// Each light vertex on a surface, with its BSDF built (its textures
// evaluated) once: stored for the eye subpaths, connected to the camera
// (t = 1), then continued by sampling the BSDF with importance transport.
void Bdpt::light_shade_stage(BdptWave& w) const {
  const uint32_t depth = w.depth, dim = dims::vertex(depth), maxdepth = uint32_t(settings_.maxdepth);
  const bool media = !scene_.media.empty();
  for_each_binned_bsdf(w.hits, scene_, [&](uint32_t i, const auto& bsdf) {
    const uint32_t slot = w.active[i];
    const PathSampler& s = w.sampler[slot];
    const HitPool& h = w.hits;
    const uint32_t ld = depth + w.origin.extra_depth[slot];  // the depth path lengths count
    const auto v = surface_vertex<TransportMode::Importance>(h, i, bsdf, w.rays.geom_id[i],
                                                             media ? w.ends.medium[i] : MediumHandle{});
    if (!bsdf.is_specular()) {
      if (keeps_light_vertex(ld))
        w.vertices.push(slot, ld, w.light.beta[slot], w.light.mis[slot],
                        {.p = h.p[i], .ng = h.ng[i], .ns = h.ns[i], .wo = h.wo[i], .error_scale = h.error_scale[i],
                         .bsdf = settings_.connections ? w.vertices.bsdfs.push(bsdf) : BsdfRef{},
                         .tangent = tangent_or_null(h.tangent, i), .medium = {}, .sigma_t = Spectrum(0.f),
                         .dispersed = w.light.dispersed[slot] != 0});
      connect_camera(w, slot, ld, v, lens_numbers(camera_, s, dim + dims::kLightLens));
    }
    if (ld >= maxdepth) {  // deeper vertices would only make paths longer than maxdepth
      ++w.stats.light_ends[size_t(PathEnd::MaxDepth)];
      return;
    }
    // Guided where the BSDF is not all delta, by the importance field.
    const bool guided = guides_light() && !bsdf.is_specular();
    const GuidingField::Site site = guided ? guiding_->importance_site(v.p, v.ns, v.wo_world) : GuidingField::Site{};
    ScatterSample drawn;
    const PathEnd end = continue_subpath(
        bsdf, TransportMode::Importance, w.hits, i, v.frame, v.wo, LazyNumber(s, dim + dims::kLightBsdfComponent),
        s.get2d(dim + dims::kLightBsdfDirection), LazyNumber(s, dim + dims::kLightRoulette), depth,
        {w.light.beta[slot], w.light.mis[slot], w.light.prev_p[slot], w.light.prev_n[slot], w.light.eta_scale[slot],
         w.light.rr_scale[slot]},
        w.mis, guided ? &site.guide : nullptr, &drawn);
    if (end != PathEnd::Count) {
      ++w.stats.light_ends[size_t(end)];
      return;
    }
    if (media) w.light.medium[slot] = v.medium_towards(scene_, w.hits.next_d[i]);
    if (guided && guiding_->learning() && !drawn.specular) {
      w.light_guide.push(slot, site.leaf, v.p, site.normal_bin, drawn.wi, drawn.pdf, average(drawn.weight) * drawn.pdf,
                         drawn.bsdf_pdf, drawn.guide_pdf, w.light.beta[slot]);
      w.light_guide_depth.push_back(strategy_count(ld));
    }
  });
}

// Records the splats of the unoccluded camera connections (after the
// stream's occlusion query).
void Bdpt::splat_stage(BdptWave& w) const {
  ConnectionPool& c = w.shadow;
  for (uint32_t r = 0; r < c.rays.count; ++r) {
    if (c.rays.occluded(r)) continue;
    const SampledWavelengths& l = w.lambda[c.slot[r]];
    const RGB contrib = film_rgb(c.contrib[r], l);
    if (learns_light()) gather_for_light_guide(w, c.slot[r], c.light_s[r], c.contrib[r]);
    const bool odd = w.odd_sample(c.slot[r]);
    w.out->splats.push_back({c.p_raster[r], contrib, odd});
    Vec2 images[2];
    for (int k = camera_.seam_images(c.p_raster[r], scene_.filter.radius, images); k-- > 0;)
      w.out->splats.push_back({images[k], contrib, odd});
    if (w.out->keep_spectra) w.out->splat_spectra.resize(w.out->splats.size(), SampleSpectrum{c.contrib[r], l});
    if (w.out->keep_slots) w.out->splat_slots.resize(w.out->splats.size(), c.slot[r]);
    if (c.record)
      w.out->strategies.push_back({0, c.p_raster[r], c.tags[r].s, 1, contrib, film_rgb(c.tags[r].unweighted, l), false,
                                   c.slot[r], c.tags[r].weight, c.tags[r].rescaled, w.origin.light[c.slot[r]]});
  }
  c.rays.count = 0;
}

// Counting sort by slot, stable, so each slot's vertices stay in depth order.
void Bdpt::group_light_vertices(BdptWave& w) const {
  LightVertexPool& v = w.vertices;
  const uint32_t slots = uint32_t(v.begin.size() - 1);
  std::fill(v.begin.begin(), v.begin.end(), 0u);
  for (uint32_t s : v.slot) ++v.begin[s + 1];
  for (uint32_t s = 0; s < slots; ++s) v.begin[s + 1] += v.begin[s];
  v.order.resize(v.size());
  std::vector<uint32_t>& next = w.active;  // free until the eye subpaths start
  std::copy(v.begin.begin(), v.begin.end() - 1, next.begin());
  for (uint32_t j = 0; j < v.size(); ++j) v.order[next[v.slot[j]]++] = j;
}

}  // namespace lantern
