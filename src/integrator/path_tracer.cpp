#include "integrator/path_tracer.h"
#include "integrator/shutter.h"

#include "film/pixel_filter.h"
#include "integrator/dispersion.h"
#include "integrator/hit.h"
#include "integrator/hit_material.h"
#include "integrator/path_next_event.h"
#include "integrator/path_wave.h"
#include "integrator/shade.h"
#include "integrator/wavelengths.h"
#include "color/spectrum_conversion.h"
#include "math/frame.h"
#include "math/sampling.h"
#include "sampler/dimensions.h"
#include "geometry/surface.h"

namespace lantern {

std::vector<uint32_t> tile_order(int width, int height, int tile) {
  std::vector<uint32_t> order;
  order.reserve(size_t(width) * size_t(height));
  for (int ty = 0; ty < height; ty += tile)
    for (int tx = 0; tx < width; tx += tile)
      for (int y = ty; y < std::min(ty + tile, height); ++y)
        for (int x = tx; x < std::min(tx + tile, width); ++x)
          order.push_back(uint32_t(y) * uint32_t(width) + uint32_t(x));
  return order;
}

PathTracer::PathTracer(const Scene& scene, const LightSampler& light_sampler, const PathTracerSettings& s)
    : scene_(scene),
      light_sampler_(light_sampler),
      settings_(s),
      camera_(scene.camera, s.full_width > 0 ? s.full_width : s.width, s.full_height > 0 ? s.full_height : s.height),
      sampler_(make_sampler_spec(s.sampler, s.width, s.height, s.planned_spp, s.seed)) {
  if (scene.textures.uses_footprint) footprints_ = FootprintModel(camera_, s.footprint_spp);
  split_camera_samples(s.split);
}

void PathTracer::split_camera_samples(uint32_t split) {
  const PathTracerSettings& s = settings_;
  settings_.split = split;
  split_log2_ = 0;
  split_pixels_.clear();
  if (split <= 1 || !scene_.media.empty() || s.ambient_occlusion || s.direct_lighting) return;
  while ((2u << split_log2_) <= split) ++split_log2_;
  // The camera samples are a sequence of their own: N paths per pixel
  // are N / split camera samples, each stratified against the others.
  const uint32_t planned = s.planned_spp > 0 ? std::max(1u, s.planned_spp >> split_log2_) : 0u;
  camera_sampler_ = make_sampler_spec(s.sampler, s.width, s.height, planned, s.seed ^ 0x5EED5EED5EED5EEDULL);
  split_pixels_ = find_split_pixels(s.ray_backend);
}

WavePools<PathWave> PathTracer::make_wave_state(uint32_t capacity, RayStream stream) const {
  return make_wave_pools<PathWave>(capacity, std::move(stream), !scene_.media.empty());
}

void PathTracer::generate_camera_rays(const WaveDesc& wave, PathWave& w) const {
  w.rays.count = 0;
  w.slots = wave.size();
  // (one sample per pixel and wave, or a Markov chain's: no groups)
  w.split = split_log2_ > 0 && wave.samples > 1 && !wave.chains;
  const uint32_t group_mask = (1u << split_log2_) - 1;
  const uint32_t width = uint32_t(settings_.width);
  for (uint32_t slot = 0; slot < wave.size(); ++slot) {
    uint32_t pixel = wave.pixels[slot / wave.samples];
    uint32_t sample_index = wave.first_sample + slot % wave.samples;
    PathSampler s = PathSampler::make(sampler_, pixel, sample_index);
    if (w.split) {
      // A camera sample's paths are adjacent slots of the pixel; the first
      // one's camera ray stands for all.
      const bool splits = splits_pixel(pixel);
      if (splits && slot % wave.samples != 0 && (sample_index & group_mask) != 0) {
        follow_camera_sample(w, slot, w.leader[slot - 1], s);
        continue;
      }
      w.leader[slot] = slot;
      w.camera_sampler[slot] = splits ? PathSampler::make(camera_sampler_, pixel, sample_index >> split_log2_) : s;
    }
    const PathSampler& cs = w.split ? w.camera_sampler[slot] : s;
    Vec2 p_raster =
        sample_raster_position(scene_.filter, pixel, width, cs.get2d(dims::kFilm)) + settings_.raster_offset;
    const float time = sample_time(scene_, cs, settings_.maxdepth);
    std::optional<Camera> moved;
    CameraRay r = camera_at(camera_, time, moved).generate_ray(p_raster, lens_numbers(camera_, cs, dims::kLens));
    w.pixel[slot] = pixel;
    w.sampler[slot] = s;
    w.lambda[slot] = sample_wavelengths(settings_.spectral, cs, settings_.maxdepth, settings_.wavelengths);
    w.time[slot] = time;
    w.beta[slot] = Spectrum(r.weight);
    w.dispersed[slot] = 0;
    w.L[slot] = Spectrum(0.f);
    w.prev_pdf[slot] = 1.f;
    w.eta_scale[slot] = 1.f;
    w.prev_specular[slot] = 1;
    w.prev_p[slot] = r.o;
    w.prev_n[slot] = Vec3(0.f);
    w.active[w.rays.count] = slot;
    w.rays.push(r.o, r.d, 0.f, kInfinity, time);
  }
  if (traces_media()) std::fill(w.medium.begin(), w.medium.begin() + wave.size(), scene_.media.camera);
}

// A path of a split camera sample starts as its leader's: the same
// wavelengths, time and camera weight; it has no ray of its own.
void PathTracer::follow_camera_sample(PathWave& w, uint32_t slot, uint32_t leader, const PathSampler& s) const {
  w.pixel[slot] = w.pixel[leader];
  w.sampler[slot] = s;
  w.leader[slot] = leader;
  w.lambda[slot] = w.lambda[leader];
  w.time[slot] = w.time[leader];
  w.beta[slot] = w.beta[leader];
  w.dispersed[slot] = 0;
  w.L[slot] = Spectrum(0.f);
  w.prev_pdf[slot] = 1.f;
  w.eta_scale[slot] = 1.f;
  w.prev_specular[slot] = 1;
  w.prev_p[slot] = w.prev_p[leader];
  w.prev_n[slot] = Vec3(0.f);
}

// The first hits of split camera samples, copied to the other paths of
// each: every path samples the BSDF there with its own numbers.
void PathTracer::branch_first_hits(PathWave& w) const {
  for (auto& bin : w.hits.bins) {
    const size_t n = bin.size();  // (the copies join the bin)
    for (size_t b = 0; b < n; ++b) {
      const uint32_t i = bin[b], leader = w.active[i];
      for (uint32_t f = leader + 1; f < w.slots && w.leader[f] == leader; ++f) {
        const uint32_t j = w.rays.push_copy(i);
        w.hits.copy(i, j);
        ++w.stats.eye_vertices;  // (each path has the vertex)
        w.active[j] = f;
        w.beta[f] = w.beta[leader];
        w.dispersed[f] = w.dispersed[leader];
      }
    }
  }
}

// What the camera sample's first hit gathered (its emission, its
// next-event estimate) belongs to each of its paths: so the film's mean
// over the paths is the camera sample's estimate plus the mean of the
// paths' continuations.
void PathTracer::share_first_hit_light(PathWave& w) const {
  for (uint32_t slot = 0; slot < w.slots; ++slot)
    if (w.leader[slot] != slot) w.L[slot] = w.L[w.leader[slot]];
}

// Hit reconstruction, emission with MIS, maxdepth, and binning by material.
void PathTracer::surface_stage(PathWave& w) const {
  w.hits.clear_bins();
  w.shadow.count = 0;
  const ShapePools& shapes = scene_.shapes;
  const LightPools& lights = scene_.lights;
  const bool at_maxdepth = int(w.depth) == settings_.maxdepth + 1;  // only emission counts this deep
  const bool media = traces_media();
  const bool occlusion = settings_.ambient_occlusion;
  const bool learning = guiding_ && guiding_->learning();
  if (media) w.scattered.clear();
  for (uint32_t i = 0; i < w.rays.count; ++i) {
    uint32_t slot = w.active[i];
    w.hits.alive[i] = 0;
    // pbrt-v3's directlighting: after a non-specular bounce too (the
    // emission its BSDF sample finds, weighted against next-event
    // estimation's, and nothing further).
    const bool last = at_maxdepth || (settings_.direct_lighting && !w.prev_specular[slot]);
    Vec3 d = glm::normalize(w.rays.direction(i));
    bool unweighted = w.prev_specular[slot] != 0;
    // In a medium the BSDF strategy's density of what the ray reaches
    // includes the probability of getting there: see next_event.
    float prev_pdf = w.prev_pdf[slot];
    if (media) {
      const SegmentEnd end = w.ends.end[i];
      const Spectrum beta_before = w.beta[slot];
      w.beta[slot] *= w.ends.weight[i];
      prev_pdf *= w.ends.fwd_density[i];
      if (end == SegmentEnd::Absorbed) {
        ++w.stats.eye_ends[size_t(PathEnd::Absorbed)];
        continue;
      }
      if (end == SegmentEnd::Scatter) {
        if (!last && !w.ends.emission.empty() && !is_black(w.ends.emission[i])) add_volume_emission(w, i, beta_before, prev_pdf);
        if (last) ++w.stats.eye_ends[size_t(PathEnd::MaxDepth)];
        else w.scattered.push_back(i);
        continue;
      }
    }
    if (!w.rays.hit(i)) {
      ++w.stats.eye_ends[size_t(PathEnd::Escaped)];
      // Each infinite light weighted against next-event estimation's
      // density of choosing it (`infinite_light_Le` says why one at a time).
      for (uint32_t k = 0; k < lights.infinite.size() && !occlusion; ++k) {
        Spectrum Le = infinite_light_Le(lights, scene_.textures, k, w.prev_p[slot], d, w.lambda[slot]);
        if (is_black(Le)) continue;
        float weight =
            unweighted ? 1.f
                       : power_heuristic(prev_pdf, infinite_light_sampled_pdf(lights, scene_.textures, light_sampler_,
                                                                              k, w.prev_p[slot], d));
        w.L[slot] += w.beta[slot] * weight * Le;
      }
      continue;
    }
    ++w.stats.eye_vertices;
    SurfacePoint sp = hit_point(shapes, w.rays, i);
    if (learning) w.guide.reached(slot, sp.p);
    if (occlusion) {
      occlusion_ray(w, slot, sp, d);
      ++w.stats.eye_ends[size_t(PathEnd::MaxDepth)];
      continue;
    }
    if (int64_t area = hit_area_light(shapes, w.rays, i); area >= 0) {
      uint32_t light = uint32_t(area);
      Spectrum Le = area_light_Le(lights.area[light], scene_.textures, sp.ng, sp.uv, -d, w.lambda[slot]);
      if (!is_black(Le)) {
        float weight = unweighted ? 1.f
                                  : power_heuristic(prev_pdf,
                                                    area_light_pdf(lights, shapes, light_sampler_, light, w.prev_p[slot],
                                                                   w.prev_n[slot], sp.p, sp.ng));
        w.L[slot] += w.beta[slot] * weight * Le;
      }
    }
    if (last) {
      ++w.stats.eye_ends[size_t(PathEnd::MaxDepth)];
      continue;
    }
    Footprint fp;
    MaterialHandle material = hit_material(scene_, footprints_, w.rays, i, d, &sp, &fp);
    scatter_at(scene_.materials, material, settings_.spectral, w.beta[slot], w.dispersed[slot]);
    w.hits.store(i, sp, d, material, w.lambda[slot], footprints_.enabled() ? &fp : nullptr);
  }
}

// Next-event estimation and BSDF sampling in one loop per material kind,
// the BSDF built once (two loops cost 3% of the path tracer's throughput:
// docs/performance.md).
void PathTracer::shade_stage(PathWave& w) const {
  const Scene& sc = scene_;
  for_each_binned_bsdf(w.hits, sc, [&](uint32_t i, const auto& bsdf) {
    uint32_t slot = w.active[i];
    const PathSampler& s = w.sampler[slot];
    const uint32_t dim = dims::vertex(w.bounce());
    const auto v = surface_vertex<TransportMode::Radiance>(w.hits, i, bsdf, w.rays.geom_id[i],
                                  sc.media.empty() ? MediumHandle{} : w.ends.medium[i]);
    const Vec3& wo = v.wo;
    // A split camera sample's first hit: its leader estimates next events
    // once, with the camera sample's numbers.
    const bool first_of_split = w.split && w.depth == 1;
    const PathSampler& s_light = first_of_split ? w.camera_sampler[slot] : s;
    const LazyNumber u_light(s_light, dim + dims::kEyeLightSelect);
    // Guided where the BSDF is not all delta.
    const bool guided = guides() && !bsdf.is_specular();
    const GuidingField::Site site = guided ? guiding_->site(v.p, v.ns, v.wo_world) : GuidingField::Site{};
    const GuideAt& guide = site.guide;
    if (!bsdf.is_specular() && !(first_of_split && w.leader[slot] != slot))
      path_next_event(sc, light_sampler_, w, slot, v, u_light, s_light.get2d(dim + dims::kEyeLightPosition),
                      volume_number(w, slot), settings_.maxdepth);
    // Continue the path by sampling the BSDF, or the mixture with the guide.
    const LazyNumber uc(s, dim + dims::kEyeBsdfComponent), u_rr(s, dim + dims::kEyeRoulette);
    auto bs =
        sample_scatter(bsdf, v.frame, wo, guide, uc, s.get2d(dim + dims::kEyeBsdfDirection), TransportMode::Radiance);
    if (!bs) {
      ++w.stats.eye_ends[size_t(PathEnd::Absorbed)];
      return;
    }
    const Vec3 wi = bs->wi;
    w.beta[slot] *= bs->weight;
    w.prev_pdf[slot] = bs->bsdf_pdf;  // MIS with light sampling: the BSDF's density (path_next_event.h)
    w.prev_specular[slot] = bs->specular;
    if (bs->transmission) w.eta_scale[slot] *= sqr(bs->etap);
    if (!survives_roulette(w.beta[slot], w.eta_scale[slot], settings_.roulette_scale, w.depth >= 2, u_rr)) {
      ++w.stats.eye_ends[size_t(PathEnd::Roulette)];
      return;
    }
    if (!is_finite(w.beta[slot])) {
      ++w.stats.eye_ends[size_t(PathEnd::Absorbed)];
      return;
    }
    if (guided && guiding_->learning() && !bs->specular)
      w.guide.push(slot, site.leaf, v.p, site.normal_bin, wi, bs->pdf, average(bs->weight) * bs->pdf, bs->bsdf_pdf,
                   bs->guide_pdf, w.beta[slot]);
    w.hits.alive[i] = 1;
    w.prev_p[slot] = w.hits.p[i];
    w.prev_n[slot] = w.hits.ns[i];
    w.hits.next_o[i] = offset_ray_origin(w.hits.p[i], w.hits.ng[i], w.hits.error_scale[i], wi);
    w.hits.next_d[i] = wi;
    if (!sc.media.empty()) w.medium[slot] = medium_after(sc, w.rays.geom_id[i], w.hits.ng[i], wi, w.ends.medium[i]);
  });
}

// pbrt-v4's ambient occlusion: a direction about the geometric normal on
// the camera's side (the shading normal plays no part), white in the
// colour space's illuminant where the ray leaves the hemisphere unblocked
// within the distance, weighted cos / (pi pdf) so a surface open to the
// whole hemisphere is 1 whichever way it samples.
void PathTracer::occlusion_ray(PathWave& w, uint32_t slot, const SurfacePoint& sp, const Vec3& d) const {
  const Vec3 n = glm::dot(sp.ng, d) > 0.f ? -sp.ng : sp.ng;
  const Vec2 u = w.sampler[slot].get2d(dims::vertex(0) + dims::kEyeBsdfDirection);
  const Vec3 local = settings_.ao_cos_sample ? sample_cosine_hemisphere(u) : sample_uniform_hemisphere(u);
  const float pdf = settings_.ao_cos_sample ? cosine_hemisphere_pdf(local.z) : uniform_hemisphere_pdf();
  if (!(pdf > 0.f) || !(local.z > 0.f)) return;
  const Vec3 wi = Frame::from_z(n).from_local(local);
  const uint32_t r = w.shadow.push(offset_ray_origin(sp.p, n, sp.error_scale, wi), wi, 0.f, settings_.ao_max_distance,
                                   w.time[slot]);
  w.shadow_slot[r] = slot;
  w.shadow_contrib[r] = illuminant_spectrum(RGB(1.f), w.lambda[slot]) * (local.z / (kPi * pdf));
}

void PathTracer::shadow_stage(PathWave& w) const {
  for (uint32_t r = 0; r < w.shadow.count; ++r)
    if (!w.shadow.occluded(r)) {
      w.L[w.shadow_slot[r]] += w.shadow_contrib[r];
      ++w.stats.light_samples_unoccluded;  // every shadow ray here is a light sample's
    }
}

void PathTracer::trace(const WaveDesc& wave, PathWave& w, WaveOutput& out) const {
  WaveStats& st = w.stats;
  {
    StageTimer t(st, Stage::Generate);
    generate_camera_rays(wave, w);
  }
  w.depth = 1;
  w.guide.clear();
  const bool learning = guiding_ && guiding_->learning();
  const bool media = traces_media();
  w.stream.intersect(w.rays, RayKind::Camera);
  for (;;) {
    if (media) segment_stage(w, w.depth == 1 ? RayKind::Camera : RayKind::Extension);
    {
      StageTimer t(st, Stage::Surface);
      surface_stage(w);
      if (w.split && w.depth == 1) branch_first_hits(w);
    }
    {
      StageTimer t(st, Stage::Shade);
      shade_stage(w);
      if (media) medium_scatter_stage(w);
    }
    if (media) {
      trace_transmittance(scene_, w.stream, w.shadow, w.shadow_medium, w.shadow_lambda, w.shadow_T, w.shadow_T_mis,
                          w.crossing);
    } else {
      w.stream.occluded(w.shadow);
    }
    {
      StageTimer t(st, Stage::Accumulate);
      if (media) media_shadow_stage(w);
      else shadow_stage(w);
      if (w.split && w.depth == 1) share_first_hit_light(w);
      if (learning) w.guide.end_bounce(w.L);
    }
    {
      StageTimer t(st, Stage::Shade);
      w.hits.compact(w.rays, w.active);
    }
    if (w.rays.count == 0) break;
    ++w.depth;
    w.stream.intersect(w.rays, RayKind::Extension);
  }
  if (learning) {
    StageTimer t(st, Stage::Accumulate);
    w.guide.make_records(w.L, guiding_->tree(), hash_key(settings_.seed, wave.pixels[0], wave.first_sample), out.guide,
                         &guiding_->scatter_field());
  }
  for (uint32_t slot = 0; slot < wave.size(); ++slot) {
    // A split camera sample's paths go to the same half of the film's
    // samples (adaptive sampling's two estimates must be independent):
    // its paths' indices differ below the halves' bit (halves_bit).
    const uint32_t index = wave.first_sample + slot % wave.samples;
    const PathSampler& cs = w.split ? w.camera_sampler[w.leader[slot]] : w.sampler[slot];
    out.samples.push_back({w.pixel[slot], film_rgb(w.L[slot], w.lambda[slot]), wave.odd(index),
                           scene_.filter.is_signed() && pixel_filter_negative(scene_.filter, cs.get2d(dims::kFilm))});
  }
  if (out.keep_spectra)
    for (uint32_t slot = 0; slot < wave.size(); ++slot) out.sample_spectra.push_back({w.L[slot], w.lambda[slot]});
}

}  // namespace lantern
