// Eye subpaths of the bidirectional tracer and the strategies that end on
// them: s = 0 (the eye subpath finds an emitter), s = 1 (next-event
// estimation) and s >= 2 (connections to the slot's stored light vertices).
#include "integrator/bdpt.h"

#include "film/pixel_filter.h"
#include "integrator/bdpt_strategies.h"
#include "integrator/bdpt_wave.h"
#include "integrator/dispersion.h"
#include "integrator/hit.h"
#include "integrator/hit_material.h"
#include "integrator/shade.h"
#include "integrator/shutter.h"
#include "light/emission.h"
#include "sampler/dimensions.h"

namespace lantern {

Bdpt::Bdpt(const Scene& scene, const LightSampler& light_sampler, const BdptSettings& s)
    : scene_(scene),
      light_sampler_(light_sampler),
      emission_choice_(s.light_choice.size() == scene.lights.all.size() ? Distribution1D(s.light_choice)
                                                                        : scene.lights.selection),
      settings_(s),
      camera_(scene.camera, s.full_width > 0 ? s.full_width : s.width, s.full_height > 0 ? s.full_height : s.height,
              scene.filter.radius),
      mis_{s.mis_beta},
      sampler_(make_sampler_spec(s.sampler, s.width, s.height, s.planned_spp, s.seed)),
      light_start_(make_light_start_spec(sampler_, s.width, s.height)) {
  if (scene.textures.uses_footprint) footprints_ = FootprintModel(camera_, s.footprint_spp);
  const float q = s.light_subpath_rate;
  mis_.with_light = mis_(q);
  mis_.without_light = mis_(1.f / q);  // (q >= 0.01: check_options)
}

WavePools<BdptWave> Bdpt::make_wave_state(uint32_t capacity, RayStream stream) const {
  return make_wave_pools<BdptWave>(capacity, std::move(stream), !scene_.media.empty());
}

void Bdpt::start_eye_subpaths(const WaveDesc& wave, BdptWave& w) const {
  w.rays.count = 0;
  w.shadow.rays.count = 0;
  const uint32_t width = uint32_t(settings_.width);
  for (uint32_t slot = 0; slot < wave.size(); ++slot) {
    const PathSampler& s = w.sampler[slot];
    uint32_t pixel = w.pixel[slot];
    if (!wave.takes_eye(pixel)) continue;
    const Vec2 p_raster = w.chains ? w.raster[slot] = metropolis_raster(s.get2d(dims::kFilm))
                                   : sample_raster_position(scene_.filter, pixel, width, s.get2d(dims::kFilm)) +
                                         settings_.raster_offset;
    std::optional<Camera> moved;
    const Camera& camera = camera_at(camera_, w.time[slot], moved);
    CameraRay r = camera.generate_ray(p_raster, lens_numbers(camera, s, dims::kLens));
    w.eye.beta[slot] = Spectrum(r.weight);
    w.eye.dispersed[slot] = 0;
    w.eye.mis[slot] = mis_camera_start(camera.pdf_dir(r.d), w.mis);
    w.eye.prev_p[slot] = r.o;
    w.eye.prev_n[slot] = Vec3(0.f);
    w.eye.eta_scale[slot] = 1.f;
    w.active[w.rays.count] = slot;
    w.rays.push(r.o, r.d, 0.f, kInfinity, w.time[slot]);
  }
  if (!scene_.media.empty())
    for (uint32_t slot = 0; slot < wave.size(); ++slot) {
      w.eye.medium[slot] = scene_.media.camera;
      w.eye.sigma_prev[slot] = Spectrum(0.f);
    }
}

// s = 0: emission found by the eye subpath; then hits are binned by material.
void Bdpt::eye_surface_stage(BdptWave& w) const {
  const bool learning = guides_eye() && guiding_->learning();
  w.hits.clear_bins();
  const ShapePools& shapes = scene_.shapes;
  const LightPools& lights = scene_.lights;
  const bool last = int(w.depth) == settings_.maxdepth + 1;  // only emission counts this deep
  const bool media = !scene_.media.empty();
  if (media) w.scattered.clear();
  for (uint32_t i = 0; i < w.rays.count; ++i) {
    uint32_t slot = w.active[i];
    w.hits.alive[i] = 0;
    Vec3 d = glm::normalize(w.rays.direction(i));
    MisState& m = w.eye.mis[slot];
    if (media && w.ends.end[i] == SegmentEnd::Absorbed) {
      ++w.stats.eye_ends[size_t(PathEnd::Absorbed)];
      continue;
    }
    if (media && w.ends.end[i] == SegmentEnd::Scatter) {  // a vertex in a medium
      ++w.stats.eye_vertices;
      const Vec3 p = w.ends.p[i], prev = w.eye.prev_p[slot];
      const float dist2 = glm::dot(p - prev, p - prev);
      if (!(dist2 > 0.f)) continue;
      mis_after_hit(m, dist2, 1.f, !(w.depth == 1 && camera_.area_sensor()), w.mis);
      const Spectrum beta_before = w.eye.beta[slot];
      apply_segment(w, w.eye, i);
      if (!last && !w.ends.emission.empty() && !is_black(w.ends.emission[i])) add_volume_emission(w, i, beta_before);
      if (last) ++w.stats.eye_ends[size_t(PathEnd::MaxDepth)];
      else w.scattered.push_back(i);
      continue;
    }
    if (!w.rays.hit(i)) {
      ++w.stats.eye_ends[size_t(PathEnd::Escaped)];
      if (media) apply_segment(w, w.eye, i);
      add_escaped_emission(w, slot, d);
      continue;
    }
    ++w.stats.eye_vertices;
    SurfacePoint sp = hit_point(shapes, w.rays, i);
    if (learning) w.guide.reached(slot, sp.p);
    Vec3 prev = w.eye.prev_p[slot];
    float dist2 = glm::dot(sp.p - prev, sp.p - prev);
    float cos_in = std::fabs(glm::dot(sp.ng, d));
    if (!(cos_in > 0.f) || !(dist2 > 0.f)) continue;
    // An area sensor's (thin-lens orthographic) first density is per area already.
    mis_after_hit(m, dist2, cos_in, !(w.depth == 1 && camera_.area_sensor()), w.mis);
    if (media) apply_segment(w, w.eye, i);
    if (int64_t light = hit_area_light(shapes, w.rays, i); light >= 0) {
      Spectrum Le = area_light_Le(lights.area[size_t(light)], scene_.textures, sp.ng, sp.uv, -d, w.lambda[slot]);
      if (!is_black(Le)) {
        uint32_t a = uint32_t(light);
        float wt, rescaled = 0.f;
        if (w.depth == 1) {
          float pos_pdf = emission_choice_.discrete_pmf(lights.area_to_all[a]) *
                          area_point_density(shapes, lights.area[a], sp.p, sp.ng);
          wt = mis_weight_hit_light_direct(m, pos_pdf, w.mis);
        } else {
          wt = mis_weight_hit_light(
              m, area_light_direct_pdf_area(lights, shapes, light_sampler_, a, prev, w.eye.prev_n[slot], sp.p, sp.ng),
              area_emission_pdf(lights, shapes, emission_choice_, a, sp.p, sp.ng, -d), w.mis, &rescaled);
        }
        add_emission(w, slot, w.eye.beta[slot] * Le, emission_weight(m, wt), rescaled, lights.area_to_all[a]);
      }
    }
    if (last) {
      ++w.stats.eye_ends[size_t(PathEnd::MaxDepth)];
      continue;
    }
    Footprint fp;
    MaterialHandle material = hit_material(scene_, footprints_, w.rays, i, d, &sp, &fp);
    scatter_at(scene_.materials, material, settings_.spectral, w.eye.beta[slot], w.eye.dispersed[slot]);
    w.hits.store(i, sp, d, material, w.lambda[slot], footprints_.enabled() ? &fp : nullptr);
  }
}

// vcm: this wave's merging radius (its first sample pass), the factors
// eta of the MIS quantities, pi r^2 n on surfaces and 4/3 pi r^3 n in
// media (n: the wave's light subpaths, all of which each eye vertex may
// merge with), and the grid.
void Bdpt::prepare_merging(const WaveDesc& wave, BdptWave& w) const {
  w.mis = mis_;
  if (!settings_.merging) return;
  const float pass = float(wave.first_sample + 1);
  const float r = settings_.vcm_radius * std::pow(pass, 0.5f * (settings_.vcm_alpha - 1.f));
  const float area = kPi * r * r, volume = area * r * (4.f / 3.f);
  const float weighed = float(std::min(wave.size(), kMergeWeightPaths)), n = float(wave.size());
  w.vm_radius = r;
  w.mis.vm_weight = mis_(area * weighed);
  w.mis.vm_medium = medium_merging() == MergeKind::Medium ? mis_(volume * weighed) : 0.f;
  w.mis.connect = settings_.connections ? 1.f : 0.f;
  w.vm_normalization = 1.f / (area * n);
  w.vm_normalization_medium = 1.f / (volume * n);
}

// Each eye vertex on a surface, with its BSDF built (its textures
// evaluated) once: the s = 1 and s >= 2 connections that end on it (and
// its merges, with vcm), then the sampling of the subpath's next direction.
void Bdpt::eye_shade_stage(BdptWave& w) const {
  const bool media = !scene_.media.empty();
  const uint32_t depth = w.depth, dim = dims::vertex(depth);
  for_each_binned_bsdf(w.hits, scene_, [&](uint32_t i, const auto& bsdf) {
    const uint32_t slot = w.active[i];
    const PathSampler& s = w.sampler[slot];
    const auto v = surface_vertex<TransportMode::Radiance>(w.hits, i, bsdf, w.rays.geom_id[i],
                                                           media ? w.ends.medium[i] : MediumHandle{});
    if (!bsdf.is_specular()) {  // (eye vertices deeper than maxdepth are not shaded: eye_surface_stage)
      if (settings_.connections) {
        next_event(w, slot, v, LazyNumber(s, dim + dims::kEyeLightSelect), s.get2d(dim + dims::kEyeLightPosition));
        if (settings_.merging) merge_at_eye_vertex(w, slot, v);
        connect_light_vertices(w, slot, v);
        if (w.shadow.rays.count >= kMaxPendingConnections) flush_connections(w);
      } else {  // bpm, ppm: merging is all there is
        merge_at_eye_vertex(w, slot, v);
      }
      if (settings_.photon_mapping) {  // ppm: merged there, and ends
        ++w.stats.eye_ends[size_t(PathEnd::MaxDepth)];
        return;
      }
    }
    // Guided where the BSDF is not all delta (as the path tracer).
    const bool guided = guides_eye() && !bsdf.is_specular();
    const GuidingField::Site site = guided ? guiding_->site(v.p, v.ns, v.wo_world) : GuidingField::Site{};
    ScatterSample drawn;
    const PathEnd end = continue_subpath(
        bsdf, TransportMode::Radiance, w.hits, i, v.frame, v.wo, LazyNumber(s, dim + dims::kEyeBsdfComponent),
        s.get2d(dim + dims::kEyeBsdfDirection), LazyNumber(s, dim + dims::kEyeRoulette), depth,
        {w.eye.beta[slot], w.eye.mis[slot], w.eye.prev_p[slot], w.eye.prev_n[slot], w.eye.eta_scale[slot],
         settings_.eye_roulette_scale},
        w.mis, guided ? &site.guide : nullptr, &drawn);
    if (end != PathEnd::Count) {
      ++w.stats.eye_ends[size_t(end)];
      return;
    }
    if (media) w.eye.medium[slot] = v.medium_towards(scene_, w.hits.next_d[i]);
    if (guided && guiding_->learning() && !drawn.specular)
      w.guide.push(slot, site.leaf, v.p, site.normal_bin, drawn.wi, drawn.pdf, average(drawn.weight) * drawn.pdf,
                   drawn.bsdf_pdf, drawn.guide_pdf, w.eye.beta[slot]);
  });
}

// Metropolis: a camera sample drawn uniformly over the image and the
// filter's margin around it lands wherever it lies, as a splat. Splats are
// scaled by the image's pixels over the light paths (film.h), so its value
// is L times the margin's share: then its expected splat on a pixel is the
// filter-weighted mean of L there, as for a sample drawn around the pixel.
Vec2 Bdpt::metropolis_raster(Vec2 u) const {
  const Vec2 full(float(camera_.width()), float(camera_.height())), margin = scene_.filter.radius;
  return u * (full + 2.f * margin) - margin;
}

void Bdpt::metropolis_samples(const WaveDesc& wave, BdptWave& w, WaveOutput& out) const {
  const Vec2 full(float(camera_.width()), float(camera_.height())), extended = full + 2.f * scene_.filter.radius;
  const float scale = extended.x * extended.y / (full.x * full.y);
  for (uint32_t slot = 0; slot < wave.size(); ++slot) {
    if (is_black(w.L[slot])) continue;
    out.splats.push_back({w.raster[slot], film_rgb(w.L[slot] * scale, w.lambda[slot]), false});
    out.splat_slots.push_back(slot);
  }
  out.light_paths += wave.size();
}

// Adds the contributions of the unoccluded connections (after the stream's
// occlusion query).
void Bdpt::connection_stage(BdptWave& w) const {
  ConnectionPool& c = w.shadow;
  for (uint32_t r = 0; r < c.rays.count; ++r) {
    if (c.rays.occluded(r)) continue;
    w.L[c.slot[r]] += c.contrib[r];
    if (learns_light()) gather_for_light_guide(w, c.slot[r], c.light_s[r], c.contrib[r]);
    w.stats.light_samples_unoccluded += c.next_event[r];
    if (c.record) {
      const SampledWavelengths& l = w.lambda[c.slot[r]];
      w.out->strategies.push_back({w.pixel[c.slot[r]], Vec2(0.f), c.tags[r].s, c.tags[r].t, film_rgb(c.contrib[r], l),
                                   film_rgb(c.tags[r].unweighted, l), false, c.slot[r], c.tags[r].weight,
                                   c.tags[r].rescaled, c.tags[r].s >= 2 ? w.origin.light[c.slot[r]] : c.tags[r].light});
    }
  }
  c.rays.count = 0;
}

void Bdpt::flush_connections(BdptWave& w) const {
  if (w.shadow.media) trace_connections(w);
  else w.stream.occluded(w.shadow.rays);
  connection_stage(w);
}

// s = 0 for an eye subpath that left the scene along d: each infinite light
// found, weighted against the strategies that sample that light
// (`infinite_light_Le` says why one at a time).
void Bdpt::add_escaped_emission(BdptWave& w, uint32_t slot, const Vec3& d) const {
  const LightPools& lights = scene_.lights;
  const MisState& m = w.eye.mis[slot];
  const Vec3 prev = w.eye.prev_p[slot];
  for (uint32_t k = 0; k < lights.infinite.size(); ++k) {
    const Spectrum Le = infinite_light_Le(lights, scene_.textures, k, prev, d, w.lambda[slot]);
    if (is_black(Le) && !settings_.record_strategies) continue;  // (a pilot's records hold it as a zero)
    float rescaled = 0.f;
    const float wt =
        w.depth == 1 ? 1.f
                     : mis_weight_hit_light(
                           m, infinite_light_sampled_pdf(lights, scene_.textures, light_sampler_, k, prev, d),
                           infinite_emission_pdf(lights, scene_.textures, emission_choice_, k, d), w.mis, &rescaled);
    add_emission(w, slot, w.eye.beta[slot] * Le, emission_weight(m, wt), rescaled, lights.infinite_to_all[k]);
  }
}

// s = 0: emission the eye subpath found at its current depth.
void Bdpt::add_emission(BdptWave& w, uint32_t slot, const Spectrum& unweighted, float weight, float rescaled,
                        uint32_t light) const {
  if (weight == 0.f && !settings_.record_strategies) return;  // (bpm's emission past a merging vertex)
  w.L[slot] += unweighted * weight;
  if (settings_.record_strategies)
    w.out->strategies.push_back({w.pixel[slot], Vec2(0.f), 0, strategy_count(w.depth + 1),
                                 film_rgb(unweighted * weight, w.lambda[slot]), film_rgb(unweighted, w.lambda[slot]),
                                 false, slot, weight, rescaled, light});
}

void Bdpt::trace(const WaveDesc& wave, BdptWave& w, WaveOutput& out) const {
  w.out = &out;
  w.chains = wave.chains;
  w.first_sample = wave.first_sample;
  w.samples_per_pixel = wave.samples;
  w.half_bit = wave.half_bit;
  w.shadow.record = settings_.record_strategies;
  if (settings_.record_strategies) out.light_rays_by_light.assign(scene_.lights.all.size(), 0);
  WaveStats& st = w.stats;
  auto timed = [&](Stage stage, auto&& fn) {
    StageTimer t(st, stage);
    fn();
  };
  const bool media = !scene_.media.empty();
  const bool learning = guides_eye() && guiding_->learning();
  auto trace_shadows = [&] {
    if (media) trace_connections(w);
    else w.stream.occluded(w.shadow.rays);
  };
  prepare_merging(wave, w);
  prepare_light_learning(w, wave.size());
  timed(Stage::Generate, [&] { start_light_subpaths(wave, w); });
  trace_shadows();
  timed(Stage::Accumulate, [&] { splat_stage(w); });
  for (w.depth = 1; w.rays.count > 0; ++w.depth) {
    w.stream.intersect(w.rays, RayKind::LightExtension);
    if (media) segment_stage(w, RayKind::LightExtension, true);
    timed(Stage::Surface, [&] { light_surface_stage(w); });
    timed(Stage::Shade, [&] {
      light_shade_stage(w);
      if (media) light_medium_stage(w);
      w.hits.compact(w.rays, w.active);
    });
    trace_shadows();
    timed(Stage::Accumulate, [&] { splat_stage(w); });
  }
  if (!settings_.light_tracing_only) {
    timed(Stage::Generate, [&] {
      group_light_vertices(w);
      if (settings_.merging) {
        const auto t0 = w.stats.timing ? TraceClock::now() : TraceClock::time_point();
        w.grid.build(w.vertices.p, w.vm_radius);
        if (w.stats.timing) w.stats.grid_seconds += std::chrono::duration<double>(TraceClock::now() - t0).count();
        w.stats.last_pass = std::max(w.stats.last_pass, wave.first_sample);
      }
      start_eye_subpaths(wave, w);
    });
    w.guide.clear();
    for (w.depth = 1; w.rays.count > 0; ++w.depth) {
      const RayKind kind = w.depth == 1 ? RayKind::Camera : RayKind::Extension;
      w.stream.intersect(w.rays, kind);
      if (media) segment_stage(w, kind, false);
      timed(Stage::Surface, [&] { eye_surface_stage(w); });
      // (a flush of a full connection pool inside this stage is counted in it)
      timed(Stage::Shade, [&] {
        eye_shade_stage(w);
        if (media) eye_medium_stage(w);
        w.hits.compact(w.rays, w.active);
      });
      trace_shadows();
      timed(Stage::Accumulate, [&] {
        connection_stage(w);
        // What a vertex's direction brought back is what the sample
        // gathers after this bounce's connections, merges and emission.
        if (learning) w.guide.end_bounce(w.L);
      });
    }
    if (learning) {
      StageTimer t(st, Stage::Accumulate);
      w.guide.make_records(w.L, guiding_->tree(), hash_key(settings_.seed, wave.pixels[0], wave.first_sample),
                           out.guide);
    }
    if (learns_light()) {
      StageTimer t(st, Stage::Accumulate);
      make_light_guide_records(wave, w, out);
    }
  }
  if (w.chains) return metropolis_samples(wave, w, out);
  for (uint32_t slot = 0; slot < wave.size(); ++slot) {
    if (!wave.takes_eye(w.pixel[slot])) continue;
    out.samples.push_back(
        {w.pixel[slot], film_rgb(w.L[slot], w.lambda[slot]), wave.odd(wave.first_sample + slot % wave.samples),
         scene_.filter.is_signed() && pixel_filter_negative(scene_.filter, w.sampler[slot].get2d(dims::kFilm))});
    if (out.keep_spectra) out.sample_spectra.push_back({w.L[slot], w.lambda[slot]});
  }
  out.light_paths += wave.size();
  for (uint32_t k = 0; k < wave.samples; ++k)  // the odd half's (adaptive sampling's estimate)
    if (wave.odd(wave.first_sample + k)) out.odd_light_paths += wave.pixel_count;
}

}  // namespace lantern
