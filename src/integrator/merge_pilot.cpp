#include "integrator/merge_pilot.h"

#include <tbb/enumerable_thread_specific.h>
#include <tbb/global_control.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <string>
#include <vector>

#include "integrator/adaptive_sampling.h"
#include "integrator/agreement.h"
#include "integrator/bdpt_wave.h"
#include "integrator/pilot.h"
#include "integrator/render_checkpoints.h"
#include "math/rng.h"
#include "scene/scene.h"

namespace lantern {

namespace {

// Per pixel of the grid: per seed, the sum of its camera samples over the
// pilot's passes, and its value (camera samples and the splats its cell
// receives, as the render would weigh them); over both seeds, the splats'
// second moment.
class VcmMoments {
 public:
  // splat_scale: what a splat landing in a cell counts for in one pixel of
  // the render (the render's light subpaths per pass over the pilot's,
  // over the pixels of a cell).
  VcmMoments(const PilotGrid& grid, double splat_scale) : grid_(grid), splat_scale_(splat_scale) {
    const size_t n = grid.pixels.size();
    camera_.assign(n, {0.0, 0.0});
    camera_square_.assign(n, 0.0);
    value_.assign(n, {0.0, 0.0});
    splat_square_.assign(n, 0.0);
  }

  void add(int seed, const WaveOutput& out) {
    for (const FilmSample& f : out.samples) {
      const double v = double(average(f.L)) * (f.negative ? -1.0 : 1.0);
      const int g = grid_.grid_index(f.pixel);
      if (g < 0 || !std::isfinite(v)) continue;  // (as the film drops it)
      camera_[size_t(g)][size_t(seed)] += v;
      value_[size_t(g)][size_t(seed)] += v;
      camera_square_[size_t(g)] += v * v;  // (one camera sample a pixel a pass)
    }
    for (const Splat& s : out.splats) {
      const double v = double(average(s.L));
      const int g = grid_.cell_index(int(std::floor(s.p_raster.x)), int(std::floor(s.p_raster.y)));
      if (g < 0 || !std::isfinite(v)) continue;
      value_[size_t(g)][size_t(seed)] += splat_scale_ * v;
      splat_square_[size_t(g)] += splat_scale_ * v * v;
    }
  }

  // relMSE per camera sample, as EyeAloneMoments::relative_error: a
  // pixel's variance over its mean squared plus the image's, averaged over
  // the grid. The mean squared is the two seeds' means' product
  // (halves_mean_squared): with its value squared, from the same 16
  // samples as its variance, vcm's error was 0.67 to 0.90 of the one
  // renders measure on the grid's pixels against the reference's values
  // (door ajar, lantern, caustics); with the product, 0.75 to 0.96
  // (docs/vcm.md, "Merges that pay").
  double relative_error(uint32_t passes) const {
    const double n = double(passes), pixels = double(value_.size());
    double image = 0.0;
    for (const auto& v : value_) image += (v[0] + v[1]) / (2.0 * n);
    image /= pixels;
    if (!(image > 0.0) || !std::isfinite(image)) return 0.0;
    double e = 0.0;
    for (size_t g = 0; g < value_.size(); ++g) {
      const double mean = (value_[g][0] + value_[g][1]) / (2.0 * n), d = (camera_[g][0] - camera_[g][1]) / n;
      const double variance = 0.5 * d * d * n + splat_square_[g] / (2.0 * n);  // (of one pass's estimate)
      const double squared = halves_mean_squared(value_[g][0] / n, value_[g][1] / n, mean);
      if (std::isfinite(variance)) e += variance / (squared + image * image);
    }
    return e / pixels;
  }

  // Per pixel: the mean of a pass's estimate and the variance of that
  // mean over the pilot's passes (from the passes' spread).
  GridMeans means(uint32_t passes) const {
    const double n = 2.0 * double(passes);
    GridMeans m;
    m.samples = n;
    for (size_t g = 0; g < value_.size(); ++g) {
      m.mean.push_back((value_[g][0] + value_[g][1]) / n);
      m.variance.push_back(grid_mean_variance(camera_[g][0] + camera_[g][1], camera_square_[g], n, splat_square_[g]));
    }
    return m;
  }

 private:
  const PilotGrid& grid_;
  double splat_scale_;
  std::vector<std::array<double, 2>> camera_, value_;
  std::vector<double> camera_square_, splat_square_;
};

// A wave of the render's size: the grid's pixels first (on_grid: a byte a
// pixel), then the image's others in tile order (they trace light
// subpaths only).
std::vector<uint32_t> wave_pixels(const PilotGrid& grid, const std::vector<uint8_t>& on_grid, uint32_t wave_paths) {
  std::vector<uint32_t> pixels = grid.pixels;
  for (const uint32_t p : tile_order(grid.width, grid.height)) {
    if (pixels.size() >= wave_paths) break;
    if (!on_grid[p]) pixels.push_back(p);
  }
  return pixels;
}

}  // namespace

double missed_light_error(const GridMeans& vcm, const GridMeans& bdpt) {
  const size_t n = std::min(vcm.mean.size(), bdpt.mean.size());
  if (n == 0) return 0.0;
  double image = 0.0;
  for (size_t g = 0; g < n; ++g) image += vcm.mean[g] / double(n);
  if (!(image > 0.0) || !std::isfinite(image)) return 0.0;
  double e = 0.0;
  for (size_t g = 0; g < n; ++g) {
    const double missed = vcm.mean[g] - bdpt.mean[g] - kMissedLightZ * std::sqrt(vcm.variance[g] + bdpt.variance[g]);
    if (missed > 0.0 && std::isfinite(missed))
      e += missed * missed * bdpt.samples / (vcm.mean[g] * vcm.mean[g] + image * image);
  }
  return e / double(n);
}

bool merges_pay(const MergeEstimate& e) {
  const double vcm = e.vcm_error * e.vcm_cost, bdpt = e.bdpt_error * e.bdpt_cost;
  if (!(vcm > 0.0) || !std::isfinite(vcm) || !(bdpt > 0.0) || !std::isfinite(bdpt)) return true;  // (nothing measured)
  return bdpt >= kMergesClearGain * vcm;
}

bool worth_a_merge_pilot(const BdptSettings& vcm, uint32_t wave_paths) {
  return render_pays_for_pilot(vcm.planned_spp, vcm.width, vcm.height, 2.0 * kMergePilotPasses * double(wave_paths));
}

bool estimate_vcm(const Scene& scene, const LightSampler& light_sampler, const BdptSettings& vcm, uint32_t wave_paths,
                  RayBackend backend, double time_budget, MergeEstimate& e, GridMeans& means) {
  const int width = vcm.full_width > 0 ? vcm.full_width : vcm.width;
  const int height = vcm.full_height > 0 ? vcm.full_height : vcm.height;
  const PilotGrid grid(width, height, grid_pilot_stride(width, height));
  if (grid.pixels.size() > wave_paths) return false;  // (an image too small to tell)
  // The render's pass has a light subpath per pixel, the pilot's
  // wave_paths: a splat in a cell of the grid counts times this.
  const double cell = double(width) * double(height) / double(grid.pixels.size());
  VcmMoments moments(grid, double(width) * double(height) / (double(wave_paths) * cell));
  std::vector<uint8_t> on_grid(size_t(width) * size_t(height), 0);
  for (const uint32_t p : grid.pixels) on_grid[p] = 1;
  const std::vector<uint32_t> pixels = wave_pixels(grid, on_grid, wave_paths);
  // Passes from the middle of a render of the planned samples (under a
  // time budget, of 128): the merging radius shrinks pass by pass.
  const uint32_t first = std::max(1u, (vcm.planned_spp > 0 ? vcm.planned_spp : 128u) / 2);
  BdptSettings pilot = pilot_settings(vcm, width, height, 0);
  std::vector<WaveOutput> outputs(kMergePilotPasses);
  const auto start = std::chrono::steady_clock::now();
  WaveStats stats;
  for (int seed = 0; seed < 2; ++seed) {
    pilot.seed = hash_key(vcm.seed, 0x6d657267ULL, uint64_t(seed));  // (two seeds of their own)
    const Bdpt tracer(scene, light_sampler, pilot);
    using State = decltype(tracer.make_wave_state(0, RayStream(scene.accel->handle(), backend, nullptr)));
    tbb::enumerable_thread_specific<State> states([&] {
      State s = tracer.make_wave_state(uint32_t(pixels.size()), RayStream(scene.accel->handle(), backend, nullptr));
      s->stream.set_scene(scene.accel->instance_base(), &scene.shapes);
      return s;
    });
    auto trace = [&](uint32_t j) {
      WaveDesc wave{pixels.data(), uint32_t(pixels.size()), first + j, 1u};
      wave.eye_pixels = on_grid.data();
      outputs[j].clear();
      tracer.trace(wave, *states.local(), outputs[j]);
    };
    uint32_t from = 0;
    if (seed == 0 && time_budget > 0.0) {  // (a pilot that would take more than a sixteenth of the budget does not run)
      trace(from++);
      const double wave_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      const double threads = double(tbb::global_control::active_value(tbb::global_control::max_allowed_parallelism));
      const double waves_at_once = std::max(1.0, std::min(threads, double(kMergePilotPasses)));
      if (16.0 * wave_seconds * (1.0 + (2.0 * kMergePilotPasses - 1.0) / waves_at_once) > time_budget) return false;
    }
    tbb::parallel_for(from, kMergePilotPasses, trace);
    for (const WaveOutput& out : outputs) moments.add(seed, out);  // (in pass order)
    for (const State& s : states) stats += s->stats;
  }
  e.vcm_error = moments.relative_error(kMergePilotPasses);
  means = moments.means(kMergePilotPasses);
  // Rays per camera sample, as the grid pilot counts bdpt's at q = 1 (its
  // eye subpath's, its connections', its light subpath's, and about two
  // for the work that casts none and s = 1, t = 1), times vcm's factor,
  // and the merges'.
  const double samples = 2.0 * kMergePilotPasses * double(grid.pixels.size());
  const double light_paths = 2.0 * kMergePilotPasses * double(pixels.size());
  const size_t escaped = size_t(PathEnd::Escaped);
  const double eye = double(stats.eye_vertices + stats.eye_ends[escaped] + stats.light_samples +
                            stats.light_connections - stats.camera_connections);
  const double light = double(stats.light_vertices + stats.light_ends[escaped] + stats.camera_connections);
  e.vcm_cost =
      kVcmRayFactor * (eye / samples + 2.0 + light / light_paths) + kMergeRays * double(stats.merges) / samples;
  e.seconds_per_path =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() / (samples + light_paths);
  return true;
}

MergingChoice choose_merging(const Scene& scene, const LightSampler& light_sampler, const RenderOptions& opt,
                             const ImageRegion& region, uint32_t planned_spp, bool agreed) {
  MergingChoice c;
  if (opt.integrator != Integrator::Vcm || !opt.merging_pilot || opt.strategies) return c;
  // A scene that asks for photon mapping (an "sppm" Integrator, whose
  // photons per iteration are known) asked for merges.
  if (scene.settings.photons_per_iteration != 0) return c;
  // Processes that render one image choose alike from the pilot's sums,
  // but not from their clocks: under a time budget, whether the pilot fits
  // depends on time, so they merge unless they agree on one's choice.
  const bool mpi = opt.checkpoint_rank >= 0, timed = opt.time_limit_seconds > 0;
  const bool shared = (mpi && !agreed) || opt.share_count > 1;
  if (timed && (shared || opt.time_limit_seconds < kMergePilotLeastBudget)) return c;
  // A resumed render goes on as its checkpoint was made, with merges or as
  // bdpt, whatever a pilot would choose now (a larger --spp starts it
  // elsewhere; a time budget's may not fit). Under MPI one rank reads the
  // checkpoint: the others take its choice (agreed), or, not told it, run
  // the pilot, and a checkpoint of the other choice is refused, as any
  // other difference is.
  if (opt.resume && mpi && agreed && !opt.resume_reads) return c;
  if (opt.resume_reads && (!mpi || agreed)) {
    if (const std::string saved = resumed_fingerprint(opt); !saved.empty()) {
      c.merge = fingerprint_value(saved, "integrator") != name(Integrator::Bdpt);
      c.from_checkpoint = true;
      return c;
    }
  }
  const BdptSettings vcm = bdpt_settings(scene, opt, region, planned_spp);
  const uint32_t wave_paths = merging_wave_paths(uint32_t(region.width) * uint32_t(region.height), opt.wave_size);
  if (vcm.unit_weights || !worth_a_merge_pilot(vcm, wave_paths)) return c;
  MergeEstimate e;
  GridMeans vcm_means;
  if (!estimate_vcm(scene, light_sampler, vcm, wave_paths, opt.ray_backend, opt.time_limit_seconds, e, vcm_means))
    return c;
  // bdpt as it would render: its rate and choice of light, from its own
  // pilot, and its error and cost on the grid at that rate (the grid
  // pilot's bdpt half if the rate pilot did not run it: about as many
  // camera and light paths as half the grid pilot's samples).
  MergingChoice no_merges;
  no_merges.merge = false;
  const RenderOptions as_bdpt = rendered_as(opt, no_merges, scene);
  BdptSettings bdpt = bdpt_settings(scene, as_bdpt, region, planned_spp);
  const PathTracerSettings eye_alone = path_settings(scene, as_bdpt, region, planned_spp);
  const bool alone = may_render_eye_subpaths_alone(scene, as_bdpt) && worth_a_grid_pilot(bdpt);
  c.bdpt = choose_light_subpath_rate(scene, light_sampler, bdpt, opt.ray_backend, alone ? &eye_alone : nullptr,
                                     opt.time_limit_seconds, opt.light_choice == LightChoiceKind::Auto);
  const float q = c.bdpt->rate;
  if (q > 0.f) bdpt.light_choice = c.bdpt->light_choice;
  std::optional<EyeAloneEstimate> grid = c.bdpt->eye_alone;
  if (!grid) {
    if (timed && 16.0 * e.seconds_per_path * grid_pilot_samples() > opt.time_limit_seconds) return MergingChoice{};
    grid = estimate_eye_subpaths_alone(scene, light_sampler, bdpt, q, eye_alone, opt.ray_backend, false);
  }
  e.missed = missed_light_error(vcm_means, grid->bdpt_means);
  e.bdpt_error = (q == 0.f ? grid->alone_error : grid->bdpt_error) + e.missed;
  e.bdpt_cost = q == 0.f ? grid->alone_cost : grid->bdpt_cost;
  c.estimate = e;
  c.merge = merges_pay(e);
  return c;
}

RenderOptions rendered_as(const RenderOptions& asked, const MergingChoice& choice, const Scene& scene) {
  RenderOptions o = asked;
  if (choice.merge) return o;
  o.integrator = Integrator::Bdpt;
  o.light_subpath_rate = kLightSubpathsAuto;  // (bdpt's pilot chooses it: vcm has none to give)
  // (the waves bdpt's own default, unless they were asked for)
  const int64_t photons = scene.settings.photons_per_iteration;
  if (o.wave_size == default_wave_size(Integrator::Vcm, photons))
    o.wave_size = default_wave_size(Integrator::Bdpt, photons);
  return o;
}

void agree_on(const RenderHooks& hooks, MergingChoice& choice) {
  const MergingChoice mine = choice;
  agree_on(hooks, choice.merge);
  agree_on(hooks, choice.from_checkpoint);
  if (choice.merge == mine.merge) return;
  choice.estimate.reset();
  choice.bdpt.reset();
}

void report_merging(const MergingChoice& c, double seconds, RenderStats& stats) {
  if (!c.estimate && !c.from_checkpoint) return;
  stats.merging_pilot = c.merge ? 1 : 0;
  stats.merging_from_checkpoint = c.from_checkpoint;
  stats.merging_seconds = seconds;
  if (!c.estimate) return;
  stats.merging_error = {c.estimate->vcm_error, c.estimate->bdpt_error};
  stats.merging_cost = {c.estimate->vcm_cost, c.estimate->bdpt_cost};
  stats.merging_missed = c.estimate->missed;
}

}  // namespace lantern
