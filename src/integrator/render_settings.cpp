#include "integrator/render_settings.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <stdexcept>
#include <string>

#include "integrator/adaptive_sampling.h"
#include "integrator/eye_subpaths_alone.h"
#include "integrator/light_choice_pilot.h"
#include "math/rng.h"
#include "scene/scene.h"

namespace lantern {

namespace {

// The memory the system can give without swapping (Linux's MemAvailable),
// in bytes; 0 when it cannot be read.
double available_memory() {
  std::ifstream in("/proc/meminfo");
  std::string key;
  double kb = 0.0;
  while (in >> key >> kb) {
    if (key == "MemAvailable:") return kb * 1024.0;
    in.ignore(256, '\n');
  }
  return 0.0;
}

std::string gib(double bytes) {
  char b[32];
  std::snprintf(b, sizeof b, "%.1f GiB", bytes / (1024.0 * 1024.0 * 1024.0));
  return b;
}

// A film too large for the machine is refused before it is allocated,
// with what it needs: per pixel the colour sums (3 x 16 bytes), the sample
// count, the resolved image (3 x 4 bytes), light tracing's splat sums (3 x
// 16) and adaptive sampling's half-buffers (2 x 3 x 16, masks).
void check_film_memory(const Scene& scene, const RenderOptions& opt) {
  const ImageRegion r = image_region(scene, opt);
  const double pixels = double(r.width) * double(r.height);
  double per_pixel = 48.0 + 4.0 + 12.0;
  if (!traces_paths(opt.integrator)) per_pixel += 48.0;
  if (opt.target_error > 0 || opt.adaptive) per_pixel += 96.0 + 2.0;
  if (opt.strategies) {
    // --strategies: per (s, t) two images of double sums and two resolved
    // (72 bytes a pixel), for every strategy a path of up to maxdepth
    // bounces can take (k + 2 of length k), and a merge per length (vcm),
    // all of them at the worst.
    const double d = std::min(opt.maxdepth, 1000);
    per_pixel += 72.0 * (d * (d + 5.0) / 2.0 + (merges_vertices(opt.integrator) ? d : 0.0));
  }
  const double need = pixels * per_pixel, have = available_memory();
  if (have > 0.0 && need > have)
    throw std::invalid_argument("a " + std::to_string(r.width) + "x" + std::to_string(r.height) + " film needs about " +
                                gib(need) + " (" + std::to_string(int(per_pixel)) + " bytes a pixel), more than the " +
                                gib(have) + " this machine has available: " +
                                (opt.strategies ? "render per-strategy images (--strategies) of a smaller image or a "
                                                  "lower maxdepth, or "
                                                : "") +
                                "render a smaller image, or a part of it (--cropwindow, --pixelbounds; Film "
                                "\"cropwindow\" or \"pixelbounds\")");
}

// Film "spectral" draws its wavelengths uniformly over its range.
WavelengthRange wavelength_range(const RenderOptions& opt) {
  if (opt.spectral_buckets <= 0) return {};
  return {opt.spectral_lambda_min, opt.spectral_lambda_max};
}

}  // namespace

void check_options(const Scene& scene, const RenderOptions& opt) {
  if (uint8_t(opt.integrator) > uint8_t(Integrator::Mlt) || uint8_t(opt.mis) > uint8_t(MisHeuristic::Balance) ||
      uint8_t(opt.light_sampler) > uint8_t(LightSamplerKind::Uniform) || uint8_t(opt.ray_backend) > uint8_t(RayBackend::Packet16) ||
      uint8_t(opt.sampler.type) > uint8_t(SamplerKind::ZSobol))
    throw std::invalid_argument("an integrator, MIS heuristic, sampler, light sampler or ray back end outside its enumeration");
  const bool merging = merges_vertices(opt.integrator);
  if (merging && (!(opt.vcm_radius >= 0.f) || !std::isfinite(opt.vcm_radius) || !(opt.vcm_alpha > 0.f && opt.vcm_alpha <= 1.f)))
    throw std::invalid_argument(std::string(name(opt.integrator)) + " needs a radius >= 0 (0: automatic) and an alpha in (0, 1]");
  if (opt.spp <= 0 && opt.time_limit_seconds <= 0) throw std::invalid_argument("--spp must be positive");
  // (Far outside this range a path's weight after the roulette overflows
  // or its survivors vanish: noise, never a better image.)
  if (!(opt.roulette_scale >= 0.01f && opt.roulette_scale <= 100.f))
    throw std::invalid_argument("--roulette must be a number from 0.01 to 100 (1: pbrt-v4's Russian roulette)");
  if (opt.split != kSplitAuto && (opt.split > 16 || (opt.split & (opt.split - 1)) != 0))
    throw std::invalid_argument("--split must be auto, 1, 2, 4, 8 or 16 (paths per camera sample)");
  if (opt.light_subpath_rate != kLightSubpathsAuto && opt.light_subpath_rate != 0.f &&
      !(opt.light_subpath_rate >= 0.01f && opt.light_subpath_rate <= 1.f))
    throw std::invalid_argument("--light-subpaths must be auto, 0 or a number from 0.01 to 1 (1: every camera sample "
                                "traces one, as pbrt-v4's bdpt)");
  // (0 where paths that only a light subpath can find, as caustics of a
  // point light, would be lost, or bdpt is asked for what the path tracer
  // does not do: refused.)
  if (opt.light_subpath_rate == 0.f && uses_light_subpath_rate(opt.integrator))
    if (const std::string why = why_not_eye_subpaths_alone(scene, opt); !why.empty())
      throw std::invalid_argument("--light-subpaths 0 (the eye subpaths alone) cannot render this: " + why);
  if (scene.camera.projection == Projection::Realistic && !traces_paths(opt.integrator))
    throw std::invalid_argument(std::string("the realistic camera works with path, directlighting and ambientocclusion, "
                                            "not ") + name(opt.integrator) +
                                ": a lens system has no importance function to connect light paths to (nor in pbrt-v4)");
  if (opt.maxdepth < 0) throw std::invalid_argument("--maxdepth must be >= 0");
  if (opt.spectral_buckets != 0 &&
      (!opt.spectral || opt.spectral_buckets < 0 || opt.spectral_buckets > 4096 ||
       !(opt.spectral_lambda_min >= 360.f && opt.spectral_lambda_max <= 830.f &&
         opt.spectral_lambda_min < opt.spectral_lambda_max)))
    throw std::invalid_argument("spectral buckets need a spectral render, 1 to 4096 buckets and a range within "
                                "[360, 830] nm");
  if (opt.integrator == Integrator::Lt && scene.camera.projection == Projection::Orthographic && !(scene.camera.lens_radius > 0.f))
    throw std::invalid_argument("light tracing (--integrator lt) cannot reach an orthographic camera without a lens: "
                                "its rays are parallel, so no light path connects to it; use path or bdpt, or give the "
                                "camera a \"lensradius\"");
  if (opt.strategies && opt.integrator != Integrator::Bdpt && !merging)
    throw std::invalid_argument("per-strategy images need --integrator bdpt, vcm, bpm or ppm");
  if (opt.wave_size < 1 || opt.wave_size > (1 << 22)) throw std::invalid_argument("--wave-size must lie in [1, 4194304]");
  if (opt.strategies && !opt.checkpoint_path.empty())
    throw std::invalid_argument("per-strategy images cannot be checkpointed or resumed");
  if (opt.resume && opt.checkpoint_path.empty()) throw std::invalid_argument("resume needs a checkpoint path");
  if (opt.share_count == 0 || opt.share_index >= opt.share_count)
    throw std::invalid_argument("--part K/N needs 1 <= K <= N");
  if (opt.share_count > 1 && opt.film_path.empty())
    throw std::invalid_argument("a part of a render (--part) needs a file for its film");
  if (opt.strategies && (opt.share_count > 1 || !opt.film_path.empty()))
    throw std::invalid_argument("per-strategy images cannot be rendered in parts");
  if (opt.guiding) {
    // The field is learnt from every pixel's samples in order: a process
    // holding a share of them would learn another field and render another
    // image. (A checkpoint carries the field: a resumed run has it.)
    if (opt.integrator != Integrator::Path && opt.integrator != Integrator::Bdpt && opt.integrator != Integrator::Vcm)
      throw std::invalid_argument("path guiding (--guide) works with path, bdpt and vcm, not with " +
                                  std::string(name(opt.integrator)));
    if (opt.share_count > 1)
      throw std::invalid_argument("path guiding (--guide) needs every unit's records: not with --part");
  }
  // Light subpaths learn from what the strategies that use their vertices
  // bring: bdpt's and vcm's connections, light tracing and merges.
  if (opt.guide_light_subpaths && opt.integrator != Integrator::Bdpt && opt.integrator != Integrator::Vcm)
    throw std::invalid_argument(std::string("guided light subpaths (--guide-light) work with bdpt and vcm, not with ") +
                                name(opt.integrator));
  if (opt.guide_light_subpaths && opt.share_count > 1)
    throw std::invalid_argument("guided light subpaths (--guide-light) need every unit's records: not with --part");
  if (opt.integrator == Integrator::Mlt) {
    // A chain's state (its numbers and current sample) lives outside the
    // film: a checkpoint, a part or a rank could not carry it on.
    if (opt.share_count > 1 || !opt.checkpoint_path.empty() || !opt.film_path.empty())
      throw std::invalid_argument("mlt needs the whole render in one run: not with --part, MPI or checkpoints (its "
                                  "chains' states are not kept with the film)");
    if (opt.target_error > 0 || opt.adaptive)
      throw std::invalid_argument("mlt spends its samples where the image is bright, not by pixel: not with a target "
                                  "error (adaptive sampling)");
    if (opt.gbuffer || opt.spectral_buckets > 0)
      throw std::invalid_argument("mlt writes RGB images only: not with Film \"gbuffer\" or \"spectral\" (their "
                                  "channels come from camera samples by pixel)");
  }
  if (!opt.sampler.randomization.empty()) parse_randomization(opt.sampler.randomization);
  check_film_memory(scene, opt);
}

ImageRegion image_region(const Scene& scene, const RenderOptions& opt) {
  ImageRegion r;
  r.full_width = opt.width > 0 ? opt.width : scene.settings.width;
  r.full_height = opt.height > 0 ? opt.height : scene.settings.height;
  int x[2], y[2];
  // The command line's region over the Film's; a crop window over pixel
  // bounds (pbrt-v4's order).
  const bool own_crop = opt.crop_window[1] >= 0.f, own_bounds = !own_crop && opt.pixel_bounds[1] >= 0;
  const std::array<int, 4>& pb = own_bounds ? opt.pixel_bounds : scene.settings.pixel_bounds;
  const std::array<float, 4>& cw = own_crop ? opt.crop_window : scene.settings.crop_window;
  if (pb[1] >= 0 && !own_crop) {
    x[0] = std::clamp(pb[0], 0, r.full_width), x[1] = std::clamp(pb[1], 0, r.full_width);
    y[0] = std::clamp(pb[2], 0, r.full_height), y[1] = std::clamp(pb[3], 0, r.full_height);
  } else {
    // In floats, as pbrt-v4 multiplies them: 480 * 0.1f is 48 in a float
    // and 48.0000007 in a double, whose ceiling would start the crop a
    // pixel later than pbrt-v4's.
    for (int k = 0; k < 2; ++k) {
      x[k] = int(std::ceil(float(r.full_width) * cw[size_t(k)]));
      y[k] = int(std::ceil(float(r.full_height) * cw[size_t(2 + k)]));
    }
  }
  if (x[1] <= x[0] || y[1] <= y[0])
    throw std::invalid_argument(std::string(own_crop || own_bounds ? "the render region (--cropwindow, --pixelbounds, --pixel)"
                                                                   : "the film's cropwindow or pixelbounds") +
                                " covers no pixel of the " +
                                std::to_string(r.full_width) + "x" + std::to_string(r.full_height) + " image");
  r.x0 = x[0], r.y0 = y[0], r.width = x[1] - x[0], r.height = y[1] - y[0];
  return r;
}

BdptSettings bdpt_settings(const Scene& scene, const RenderOptions& opt, const ImageRegion& region,
                           uint32_t planned_spp) {
  BdptSettings bs;
  const bool merging = merges_vertices(opt.integrator);
  bs.maxdepth = opt.maxdepth;
  bs.seed = opt.seed;
  bs.width = region.width;
  bs.height = region.height;
  bs.full_width = region.full_width;
  bs.full_height = region.full_height;
  bs.raster_offset = Vec2(float(region.x0), float(region.y0));
  bs.mis_beta = opt.mis == MisHeuristic::Balance ? 1.f : 2.f;
  bs.light_tracing_only = opt.integrator == Integrator::Lt;
  // (auto: the render's pilot sets it, render.cpp)
  bs.light_subpath_rate = uses_light_subpath_rate(opt.integrator) && opt.light_subpath_rate != kLightSubpathsAuto ? opt.light_subpath_rate : 1.f;
  if (opt.light_choice == LightChoiceKind::Uniform) bs.light_choice = uniform_choice(scene.lights);
  bs.merging = merging;
  bs.connections = !merging || opt.integrator == Integrator::Vcm;
  bs.photon_mapping = opt.integrator == Integrator::Ppm;
  bs.vcm_alpha = opt.vcm_alpha;
  bs.vcm_radius = opt.vcm_radius > 0.f                  ? opt.vcm_radius
                  : scene.settings.merge_radius > 0.f ? scene.settings.merge_radius
                                                      : 0.003f * scene.lights.scene_radius;
  bs.unit_weights = opt.debug_unit_mis_weights;
  bs.record_strategies = opt.strategies;
  bs.footprint_spp = scene.settings.spp;
  bs.sampler = opt.sampler;
  bs.planned_spp = planned_spp;
  bs.spectral = opt.spectral;
  bs.wavelengths = wavelength_range(opt);
  return bs;
}

MetropolisSettings metropolis_settings(const Scene& scene, const RenderOptions& opt, const ImageRegion& region) {
  const SceneSettings& st = scene.settings;
  MetropolisSettings m;
  m.mutations = opt.time_limit_seconds > 0 ? 0 : uint64_t(opt.spp) * uint64_t(region.width) * uint64_t(region.height);
  m.chains = uint32_t(st.mlt_chains);
  m.bootstrap_samples = uint64_t(st.mlt_bootstrap_samples);
  m.large_step_probability = st.mlt_large_step_probability;
  m.sigma = st.mlt_sigma;
  m.seed = hash_key(opt.seed, opt.sampler.seed, 0x6D6C74ULL);
  return m;
}

uint32_t split_once_unguided(const Scene& scene, const RenderOptions& opt) {
  return splits_camera_samples(opt.integrator) && scene.media.empty() ? opt.split : 1u;
}

uint32_t camera_sample_split(const Scene& scene, const RenderOptions& opt) {
  return opt.any_guiding() ? 1u : split_once_unguided(scene, opt);
}

void check_processes(const RenderOptions& opt, const RenderHooks& hooks) {
  if (opt.target_error > 0 || opt.adaptive) {
    if (opt.target_error <= 0 && opt.time_limit_seconds <= 0 && opt.spp < int(kAdaptiveFirstSamples))
      throw std::invalid_argument(
          "adaptive sampling to a mean of " + std::to_string(opt.spp) +
          " samples per pixel: it needs 32 or more, as its first two passes give every pixel 16 each");
    // Its decisions read the whole of each pixel's samples, which one
    // process holds only when it renders them all.
    if (opt.share_count > 1 || hooks.next_ticket)
      throw std::invalid_argument(
          "adaptive sampling (a target error or a budget) needs the whole render in one process: not with "
          "--part or MPI");
  }
  if (opt.integrator == Integrator::Mlt && (hooks.next_ticket || hooks.reduce_film))
    throw std::invalid_argument("mlt needs the whole render in one process: not with MPI");
  if (opt.gbuffer && (opt.share_count > 1 || hooks.next_ticket || hooks.reduce_film))
    throw std::invalid_argument("Film \"gbuffer\" needs the whole render in one process: not with --part or MPI");
  if (opt.spectral_buckets > 0 && (opt.share_count > 1 || hooks.next_ticket || hooks.reduce_film))
    throw std::invalid_argument("Film \"spectral\" needs the whole render in one process: not with --part or MPI");
  // MPI hands out units by tickets: the ranks learn one field by sharing
  // their sums at the end of each iteration (RenderHooks::share_learnt).
  if (opt.any_guiding() && hooks.next_ticket && !hooks.share_learnt)
    throw std::invalid_argument(
        "path guiding (--guide, --guide-light) under MPI needs its ranks to share what they learn");
}

PathTracerSettings path_settings(const Scene& scene, const RenderOptions& opt, const ImageRegion& region,
                                 uint32_t planned_spp) {
  PathTracerSettings ps;
  ps.maxdepth = opt.maxdepth;
  ps.seed = opt.seed;
  ps.width = region.width;
  ps.height = region.height;
  ps.full_width = region.full_width;
  ps.full_height = region.full_height;
  ps.raster_offset = Vec2(float(region.x0), float(region.y0));
  ps.footprint_spp = scene.settings.spp;
  ps.sampler = opt.sampler;
  ps.planned_spp = planned_spp;
  ps.spectral = opt.spectral;
  ps.wavelengths = wavelength_range(opt);
  ps.direct_lighting = opt.integrator == Integrator::Direct;
  // (directlighting: pbrt-v4's rule; bdpt's eye subpaths alone: the path
  // tracer's default)
  ps.roulette_scale = scales_roulette(opt.integrator)      ? opt.roulette_scale
                      : opt.integrator == Integrator::Bdpt ? PathTracerSettings{}.roulette_scale
                                                           : 1.f;
  ps.ambient_occlusion = opt.integrator == Integrator::AmbientOcclusion;
  ps.split = camera_sample_split(scene, opt);
  ps.ray_backend = opt.ray_backend;
  ps.ao_max_distance = scene.settings.ao_max_distance;
  ps.ao_cos_sample = scene.settings.ao_cos_sample;
  return ps;
}

uint32_t merging_wave_paths(uint32_t pixels, int wave_size) {
  const uint32_t most = std::max<uint32_t>(1, uint32_t(wave_size));
  const uint32_t waves = (pixels + most - 1) / most;
  return std::max<uint32_t>(1, (pixels + waves - 1) / waves);
}

}  // namespace lantern
