#include "integrator/split_choice.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "integrator/agreement.h"
#include "integrator/path_wave.h"
#include "integrator/pilot.h"
#include "scene/scene.h"

namespace lantern {

namespace {
constexpr double kPilotPixels = 4096.0;
constexpr uint32_t kPilotSpp = 32;

// The pilot's image at one candidate and seed: each pixel's mean over its
// paths (of the channels' mean: relMSE weighs them alike).
struct PilotImage {
  std::vector<double> mean;
  double vertices_per_path = 0.0;
};

PilotImage render_pilot(const Scene& scene, const LightSampler& light_sampler, const PathTracerSettings& settings,
                        const std::vector<uint32_t>& pixels, RayBackend backend) {
  const PathTracer tracer(scene, light_sampler, settings);
  PilotImage im;
  im.mean.assign(pixels.size(), 0.0);
  const WaveStats stats =
      trace_pilot(scene, tracer, pixels, kPilotSpp, backend, [&](const WaveDesc&, size_t first, const WaveOutput& out) {
        for (size_t j = 0; j < out.samples.size(); ++j) {
          const FilmSample& s = out.samples[j];
          im.mean[first + j / kPilotSpp] += (double(s.L[0]) + double(s.L[1]) + double(s.L[2])) / 3.0;
        }
      });
  for (double& m : im.mean) m /= double(kPilotSpp);
  im.vertices_per_path = double(stats.eye_vertices) / (double(im.mean.size()) * kPilotSpp);
  return im;
}
}  // namespace

SplitChoice best_split(const std::array<double, kSplitCandidates.size()>& variance, double camera_share) {
  SplitChoice c;
  c.variance = variance;
  c.camera_share = camera_share;
  const double a = std::clamp(camera_share, 0.0, 1.0);
  if (!(variance[0] > 0.0)) return c;  // (a black image: nothing to gain)
  size_t best = 0;
  for (size_t i = 0; i < kSplitCandidates.size(); ++i) {
    const double k = double(kSplitCandidates[i]);
    c.error[i] = variance[i] > 0.0 ? variance[i] * (a / k + 1.0 - a) / variance[0] : 0.0;
    if (variance[i] > 0.0 && c.error[i] < c.error[best]) best = i;
  }
  c.split = c.error[best] <= kSplitGain ? kSplitCandidates[best] : 1u;
  return c;
}

bool worth_a_split_pilot(const PathTracerSettings& render, double time_budget) {
  if (time_budget > 0.0) return time_budget >= 8.0;
  const double pilot_paths = 2.0 * double(kSplitCandidates.size()) * kPilotPixels * kPilotSpp;
  return render_pays_for_pilot(render.planned_spp, render.width, render.height, pilot_paths);
}

SplitChoice choose_split(const Scene& scene, const LightSampler& light_sampler, const PathTracerSettings& render,
                         RayBackend backend) {
  // Every stride-th pixel of every stride-th row of the film (the crop's,
  // with one), at the image's own resolution: what a pixel sees varies
  // within it as in the render.
  const uint32_t width = uint32_t(render.width), height = uint32_t(render.height);
  const uint32_t stride = std::max(1u, uint32_t(std::ceil(std::sqrt(double(width) * double(height) / kPilotPixels))));
  PathTracerSettings pilot = render;
  pilot.planned_spp = kPilotSpp;
  pilot.probe_stride = stride;
  std::vector<uint32_t> pixels;
  for (uint32_t y = stride / 2; y < height; y += stride)
    for (uint32_t x = stride / 2; x < width; x += stride) pixels.push_back(y * width + x);
  // Two seeds of each candidate; every pixel's error relative to its value
  // squared plus the image's mean squared, its value from every candidate's images
  // alike. (From whole camera samples' alone, a rare bright path in one of
  // theirs raised its pixel's value and so lowered its own weight, while
  // one in a split image kept its full weight: the spotlit room's and the
  // lantern's pilots estimated 29 and 20 times the error for 4, where it
  // leaves 0.88 and 0.97 of it.)
  std::array<std::array<PilotImage, 2>, kSplitCandidates.size()> images;
  for (size_t i = 0; i < kSplitCandidates.size(); ++i)
    for (uint64_t s = 0; s < 2; ++s) {
      pilot.split = kSplitCandidates[i];
      pilot.seed = mix64(render.seed ^ 0x5B11D5B11D5B11DULL) + s;
      images[i][s] = render_pilot(scene, light_sampler, pilot, pixels, backend);
    }
  const size_t n = images[0][0].mean.size();
  const double per_pixel = 1.0 / (2.0 * double(kSplitCandidates.size()));
  std::vector<double> value(n, 0.0);
  double image_mean = 0.0;
  for (size_t p = 0; p < n; ++p) {
    for (const auto& pair : images) value[p] += (pair[0].mean[p] + pair[1].mean[p]) * per_pixel;
    if (std::isfinite(value[p])) image_mean += value[p] / double(n);  // (a pixel that is not: left out below)
  }
  std::array<double, kSplitCandidates.size()> variance{};
  for (size_t p = 0; p < n; ++p) {
    const double mu = value[p];
    const double weight = 1.0 / (mu * mu + image_mean * image_mean);
    if (!std::isfinite(mu) || !std::isfinite(weight)) continue;
    for (size_t i = 0; i < kSplitCandidates.size(); ++i)
      variance[i] += weight * 0.5 * std::pow(images[i][0].mean[p] - images[i][1].mean[p], 2);
  }
  return best_split(variance, 0.5 / std::max(images[0][0].vertices_per_path, 1.0));
}

void set_split(const Scene& scene, const LightSampler& light_sampler, const RenderOptions& opt,
               PathTracerSettings& render, RenderStats& stats, const RenderHooks& hooks) {
  render.split = 1;
  if (worth_a_split_pilot(render, opt.time_limit_seconds)) {
    const SplitChoice c = choose_split(scene, light_sampler, render, opt.ray_backend);
    render.split = c.split;
    stats.split_candidates.assign(kSplitCandidates.begin(), kSplitCandidates.end());
    stats.split_error.assign(c.error.begin(), c.error.end());
    stats.split_camera_share = c.camera_share;
  }
  // (every process makes the same choice from the pilot, but the processes
  // of one image make the same calls to agree, whatever they render)
  agree_on(hooks, render.split);
}

}  // namespace lantern
