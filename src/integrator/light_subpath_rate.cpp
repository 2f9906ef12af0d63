#include "integrator/light_subpath_rate.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <memory>

#include "integrator/agreement.h"
#include "integrator/bdpt_wave.h"
#include "integrator/eye_subpaths_alone.h"
#include "integrator/light_choice_pilot.h"
#include "integrator/pilot.h"
#include "light/light_sampler.h"
#include "scene/scene.h"

namespace lantern {

namespace {
// The pilot: the camera's whole image at about 64 x 64 pixels, 8 samples
// each, 0.02-0.10 s on the shipped scenes. (Measured, this predicts the
// rates' errors there better than every stride-th pixel of the image at
// its own resolution: the Cornell box's equal-time ratio at Q = 1/2, 0.93,
// was predicted 0.92 so and 1.01 that way.) Its waves are traced a batch
// at a time and their records read in wave order, then freed.
constexpr double kPilotPixels = 4096.0;
constexpr uint32_t kPilotSpp = 8;
constexpr uint32_t kTargetSpp = 2;  // the light choice's first pass (light_choice_pilot.h)
constexpr double kClearLightGain = 0.7;

// The light choice with the least relMSE at equal cost, each at its best
// rate, among those that raise neither it nor the MSE (relative to the
// image's mean squared) above power's and lower one of them by 30%: a
// choice that moves light subpaths to a dim light can lower the relative
// error of what it lights and raise the absolute error of the rest, and
// one that moves them to a light that makes a bright caustic can lower
// the MSE most. (30%: the cost counts rays, and a light subpath through a
// medium or one whose splats spread over the filter's pixels costs more
// time than its rays say; on the reading room and the smoke, gains of
// 5-23% the pilot saw were not there at equal time.) Its rates' errors
// and costs into `choice`.
using RateArray = std::array<double, kLightSubpathRates.size()>;

void pick_light_choice(const RateMoments& moments, const LightChoices& lights, const std::vector<RateArray>& costs,
                       uint32_t spp, LightSubpathRateChoice& choice) {
  std::vector<RateArray> errors;
  std::vector<double> relative, absolute;  // per candidate at its best rate, times its cost
  for (size_t c = 0; c < lights.names.size(); ++c) {
    errors.push_back(moments.relative_error(c));
    const float q = best_light_subpath_rate(errors[c], costs[c], spp);
    const size_t k =
        size_t(std::find(kLightSubpathRates.begin(), kLightSubpathRates.end(), q) - kLightSubpathRates.begin());
    choice.light_choice_error.push_back(errors[c][k]);
    choice.light_choice_mse.push_back(moments.relative_error(c, true)[k]);
    choice.light_choice_cost.push_back(costs[c][k]);
    relative.push_back(errors[c][k] * costs[c][k]);
    absolute.push_back(choice.light_choice_mse[c] * costs[c][k]);
  }
  size_t best = 0;
  for (size_t c = 1; c < lights.names.size(); ++c)
    if (relative[c] <= relative[0] && absolute[c] <= absolute[0] &&
        (relative[c] <= kClearLightGain * relative[0] || absolute[c] <= kClearLightGain * absolute[0]) &&
        relative[c] < relative[best] && relative[c] > 0.0)
      best = c;
  choice.error = errors[best];
  choice.cost = costs[best];
  if (lights.names.size() > 1)
    choice.light_choice_candidates = lights.names;
  else
    choice.light_choice_error.clear(), choice.light_choice_mse.clear(), choice.light_choice_cost.clear();
  if (best > 0) {
    choice.light_choice = lights.probabilities[best];
    choice.light_choice_name = lights.names[best];
  }
}
}  // namespace

RateMoments::RateMoments(int width, int height, uint32_t spp, float mis_beta, bool stratified,
                         std::vector<std::vector<float>> light_ratios, double splat_share)
    : stratified_(stratified),
      width_(width),
      height_(height),
      spp_(spp),
      beta_(mis_beta),
      ratios_(light_ratios.empty() ? std::vector<std::vector<float>>{{}} : std::move(light_ratios)),
      splat_share_(splat_share),
      value_(size_t(width) * size_t(height), 0.0),
      sum_(value_.size() * ratios_.size()),
      square_(sum_.size()),
      light_sum_(sum_.size()),
      splat_square_(sum_.size()),
      alone_sum_(value_.size(), 0.0),
      alone_square_(value_.size(), 0.0),
      alone_mis_(value_.size(), 0.0) {}

int RateMoments::pixel_of(const StrategyRecord& r) const {
  if (r.t >= 2) return int(r.pixel);
  const int x = int(std::floor(r.p_raster.x)), y = int(std::floor(r.p_raster.y));
  return x >= 0 && y >= 0 && x < width_ && y < height_ ? y * width_ + x : -1;
}

// 1 / w = 1 + kept + rescaled x Mis(ratio), the ratio of the other count
// class's count to this strategy's: q for a strategy run once (its others
// there need the light subpath), 1 / q for one that needs it.
float weight_at_rate(float weight, float rescaled, bool needs_light_subpath, float q, float mis_beta) {
  if (!(weight > 0.f)) return 0.f;
  const float ratio = needs_light_subpath ? 1.f / q : q;
  const float kept = std::max(0.f, 1.f / weight - 1.f - rescaled);
  return 1.f / (1.f + kept + rescaled * (mis_beta == 2.f ? ratio * ratio : ratio));
}

void RateMoments::add_values(const std::vector<StrategyRecord>& records) {
  for (const StrategyRecord& r : records) {
    const double v = double(average(r.weighted));
    if (const int p = pixel_of(r); p >= 0 && std::isfinite(v)) value_[size_t(p)] += v;  // (as the film drops it)
  }
}

void RateMoments::add(const WaveDesc& wave, const std::vector<StrategyRecord>& records) {
  add_values(records);
  add_moments(wave, records);
}

void RateMoments::add_moments(const WaveDesc& wave, const std::vector<StrategyRecord>& records) {
  for (size_t c = 0; c < ratios_.size(); ++c) add_choice_moments(wave, records, c);
  std::vector<double> alone(wave.size(), 0.0);
  for (const StrategyRecord& r : records) {
    const double u = double(average(r.unweighted));
    if (r.t >= 2 && r.s <= 1 && r.slot < wave.size()) {
      const double v = double(eye_alone_weight(r, beta_)) * u;
      if (std::isfinite(v)) alone[r.slot] += v;
    }
    if (const int p = pixel_of(r); p >= 0 && u != 0.0 && std::isfinite(u)) {
      const double m = double(r.weight) * u * u * eye_alone_density_ratio(r);
      alone_mis_[size_t(p)] += std::isfinite(m) ? m : std::numeric_limits<double>::infinity();
    }
  }
  for (uint32_t slot = 0; slot < wave.size(); ++slot) {
    const size_t p = wave.pixels[slot / wave.samples];
    alone_sum_[p] += alone[slot];
    alone_square_[p] += alone[slot] * alone[slot];
  }
}

void RateMoments::add_choice_moments(const WaveDesc& wave, const std::vector<StrategyRecord>& records, size_t choice) {
  // Per camera sample of the wave (its slot) and rate: A and B, and the
  // rho of its light subpath's light.
  std::vector<std::array<double, kRates>> once(wave.size()), with_light(wave.size());
  std::vector<double> rho(wave.size(), 1.0);
  for (const StrategyRecord& r : records) {
    const double u = double(average(r.unweighted));
    if (!(u != 0.0) || !std::isfinite(u) || !std::isfinite(double(average(r.weighted)))) continue;
    const bool needs_light_subpath = r.s >= 2;
    const float ratio = light_ratio(choice, r.light);
    // A light seen from the camera: the light's own point joined to the
    // camera (s = 1, t = 1), drawn as light subpaths start, against the
    // camera ray that hits it (s = 0, t = 2), whose only other strategy it
    // is. The rate leaves both alone; the light's rho weighs them.
    const bool seen = (r.s == 1 && r.t == 1) || (r.s == 0 && r.t == 2);
    if (seen && r.t == 1) {
      const int p = pixel_of(r);
      const double v = double(seen_weight(r, ratio)) * u, square = splat_share_ * v * v / double(ratio);
      if (p >= 0 && std::isfinite(square))
        for (size_t k = 0; k < kRates; ++k) splat_square_[at(choice, size_t(p))][k] += square;
      continue;
    }
    if (r.t == 1) {  // a splat: a sample of the pixel it lands in
      const int p = pixel_of(r);
      if (p < 0) continue;
      for (size_t k = 0; k < kRates; ++k) {
        const float count = kLightSubpathRates[k] * ratio;
        const double v = double(weight_at(r, count)) * u;
        const double square = splat_share_ * v * v;
        if (std::isfinite(square))
          splat_square_[at(choice, size_t(p))][k] += needs_light_subpath ? square / double(count) : square;
      }
      continue;
    }
    if (r.slot >= wave.size()) continue;
    if (needs_light_subpath) rho[r.slot] = double(ratio);
    auto& sums = needs_light_subpath ? with_light[r.slot] : once[r.slot];
    for (size_t k = 0; k < kRates; ++k)
      sums[k] += double(seen ? seen_weight(r, ratio) : weight_at(r, kLightSubpathRates[k] * ratio)) * u;
  }
  for (uint32_t slot = 0; slot < wave.size(); ++slot) {
    const size_t p = at(choice, wave.pixels[slot / wave.samples]);
    for (size_t k = 0; k < kRates; ++k) {
      const double a = once[slot][k], b = with_light[slot][k], count = kLightSubpathRates[k] * rho[slot];
      sum_[p][k] += a + b;
      light_sum_[p][k] += b;
      square_[p][k] += a * a + 2.0 * a * b + b * b / count;
    }
  }
}

std::vector<double> RateMoments::relative_scale(bool absolute) const {
  // (relative to the pixel's value squared plus the image's mean squared:
  // free of the image's scale, and near `lantern compare`'s 0.01 on images
  // of mean 0.1; absolute: to the image's mean squared alone)
  const double n = double(spp_);
  double image = 0.0;
  for (const double v : value_) image += v / n;
  image /= double(value_.size());
  if (!(image > 0.0) || !std::isfinite(image)) return {};  // a black image: nothing to choose by
  std::vector<double> scale(value_.size());
  for (size_t p = 0; p < value_.size(); ++p) {
    const double pixel = absolute ? 0.0 : value_[p] / n;
    scale[p] = 1.0 / (pixel * pixel + image * image);
  }
  return scale;
}

std::array<double, RateMoments::kRates> RateMoments::relative_error(size_t choice, bool absolute) const {
  std::array<double, kRates> e{};
  const double n = double(spp_);
  const std::vector<double> scale = relative_scale(absolute);
  if (scale.empty()) return e;
  for (size_t p = 0; p < value_.size(); ++p) {
    const size_t i = at(choice, p);
    for (size_t k = 0; k < kRates; ++k) {
      // The variance of the pixel's mean: its camera samples' spread, and
      // its splats' second moment.
      const double q = kLightSubpathRates[k], b = light_sum_[i][k] / n;
      double spread = square_[i][k] - sum_[i][k] * sum_[i][k] / n;
      if (stratified_) spread -= n * b * b * (1.0 / q - 1.0);
      if (!std::isfinite(spread) || !std::isfinite(splat_square_[i][k])) continue;  // (a sample the film would drop)
      e[k] += (std::max(0.0, spread) + splat_square_[i][k]) / (n * n) * scale[p];
    }
  }
  for (double& x : e) x *= n / double(value_.size());  // (per camera sample: n times the pilot image's)
  return e;
}

double RateMoments::eye_alone_error() const {
  const std::vector<double> scale = relative_scale();
  if (scale.empty()) return 0.0;
  const double n = double(spp_);
  double spread = 0.0, weighed = 0.0;
  for (size_t p = 0; p < value_.size(); ++p) {
    spread += std::max(0.0, alone_square_[p] - alone_sum_[p] * alone_sum_[p] / n) / (n * n) * scale[p];
    const double mean = value_[p] / n;
    weighed += std::max(0.0, alone_mis_[p] / n - mean * mean) / n * scale[p];
  }
  // (the second, whose paths are sampled by bdpt's strategies, leaves out
  // the covariances of one eye subpath's lengths: the larger)
  return std::max(spread, weighed) * n / double(value_.size());
}

float best_light_subpath_rate(const std::array<double, kLightSubpathRates.size()>& error,
                              const std::array<double, kLightSubpathRates.size()>& cost, uint32_t spp) {
  const double base = error[0] * cost[0];
  if (!(base > 0.0) || !std::isfinite(base)) return 1.f;  // nothing measured: pbrt-v4's bdpt
  size_t best = 0;
  for (size_t k = 1; k < kLightSubpathRates.size(); ++k)
    if ((spp == 0 || kLightSubpathRates[k] * float(spp) >= 1.f) && error[k] * cost[k] < error[best] * cost[best]) best = k;
  return error[best] * cost[best] <= 0.95 * base ? kLightSubpathRates[best] : 1.f;
}

namespace {
// The eye subpaths alone as a candidate against bdpt at the best rate k
// (eye_subpaths_alone.h): the first pilot's ratio of their errors, and
// the grid pilot where they may still pay. As this pilot sees them (their
// rays, `alone_cost`, at pbrt-v4's roulette, fewer than the path tracer's:
// in their favour) they cannot pay where the grid would have to find a
// ratio more than kPilotsAgree times below this pilot's. Under a time
// budget, only if the grid pilot, as long as this one took per sample,
// takes at most a sixteenth of it (the one choice that depends on time:
// such renders' sample counts do too).
void consider_eye_subpaths_alone(const Scene& scene, const LightSampler& light_sampler, const BdptSettings& render,
                                 const PathTracerSettings& eye_alone, RayBackend backend, const RateMoments& moments,
                                 double alone_cost, double pilot_seconds_per_sample, double time_budget,
                                 LightSubpathRateChoice& choice) {
  if (time_budget > 0.0 && 16.0 * grid_pilot_samples() * pilot_seconds_per_sample > time_budget) return;
  const float best = best_light_subpath_rate(choice.error, choice.cost, render.planned_spp);
  const size_t k = size_t(std::find(kLightSubpathRates.begin(), kLightSubpathRates.end(), best) - kLightSubpathRates.begin());
  const double ratio = choice.error[k] > 0.0 ? moments.eye_alone_error() / choice.error[k] : 0.0;
  choice.eye_alone_first_ratio = ratio;
  const double bdpt_cost = choice.cost[k] + 1.0;  // (its work that casts no ray: as the grid pilot counts it)
  if (!(ratio > 0.0 && ratio / kPilotsAgree <= kClearGain * bdpt_cost / alone_cost)) return;
  BdptSettings bdpt = render;  // (with the light choice made)
  bdpt.light_choice = choice.light_choice;
  const EyeAloneEstimate e = estimate_eye_subpaths_alone(scene, light_sampler, bdpt, best, eye_alone, backend);
  choice.eye_alone = e;
  if (e.bdpt_error > 0.0 && e.bdpt_cost > 0.0) {  // (for --stats, in this pilot's units)
    choice.eye_alone_error = choice.error[k] * e.alone_error / e.bdpt_error;
    choice.eye_alone_cost = choice.cost[k] * e.alone_cost / e.bdpt_cost;
  }
}

// The pilot's image: the render's whole image shrunk to about
// kPilotPixels.
std::pair<int, int> pilot_size(const BdptSettings& render) {
  const int full_w = render.full_width > 0 ? render.full_width : render.width;
  const int full_h = render.full_height > 0 ? render.full_height : render.height;
  const int shrink = std::max(1, int(std::ceil(std::sqrt(double(full_w) * double(full_h) / kPilotPixels))));
  return {std::max(1, full_w / shrink), std::max(1, full_h / shrink)};
}
}  // namespace

bool worth_a_rate_pilot(const Scene& scene, const BdptSettings& render, bool choose_light) {
  const auto [w, h] = pilot_size(render);
  const bool lights = choose_light && scene.lights.all.size() > 1 && render.light_choice.empty();
  const double pilot = double(w) * double(h) * kPilotSpp * (lights ? 2.0 : 1.0);
  return render_pays_for_pilot(render.planned_spp, render.width, render.height, pilot);
}

LightSubpathRateChoice choose_light_subpath_rate(const Scene& scene, const LightSampler& light_sampler,
                                                 const BdptSettings& render, RayBackend backend,
                                                 const PathTracerSettings* eye_alone, double time_budget,
                                                 bool choose_light) {
  const auto [pilot_w, pilot_h] = pilot_size(render);
  BdptSettings pilot = pilot_settings(render, pilot_w, pilot_h, kPilotSpp);
  pilot.record_strategies = true;
  pilot.light_subpath_rate = 1.f;
  // With several lights, light subpaths may choose theirs otherwise than
  // by power (light_choice_pilot.h): this pilot draws them half by power,
  // half uniformly, and weighs the candidates.
  LightChoices lights{{"power"}, {{}}};
  std::vector<std::vector<float>> ratios{{}};
  if (choose_light && scene.lights.all.size() > 1 && pilot.light_choice.empty()) {
    pilot.light_choice = first_pass_choice(scene.lights);
    lights = light_choice_candidates(power_choice(scene.lights),
                                     light_choice_target(scene, light_sampler, pilot, kTargetSpp, backend));
    ratios = light_choice_ratios(lights, pilot.light_choice);
  }
  const auto start = std::chrono::steady_clock::now();  // (this pilot's own time, per sample: the first pass's is not)
  const Bdpt bdpt(scene, light_sampler, pilot);
  RateMoments moments(pilot.width, pilot.height, kPilotSpp, pilot.mis_beta,
                      pilot.sampler.type != SamplerKind::Independent, ratios, splat_square_share(scene.filter));
  std::vector<double> light_rays(scene.lights.all.size(), 0.0);  // per light: its light subpaths' rays
  const WaveStats bdpt_stats = trace_pilot(scene, bdpt, tile_order(pilot.width, pilot.height), kPilotSpp, backend,
                                           [&](const WaveDesc& wave, size_t, const WaveOutput& out) {
                                             moments.add(wave, out.strategies);
                                             for (size_t j = 0; j < out.light_rays_by_light.size(); ++j)
                                               light_rays[j] += double(out.light_rays_by_light[j]);
                                           });
  LightSubpathRateChoice choice;
  // Rays per camera sample: what every sample casts (its eye subpath's
  // rays, each ending at a vertex or escaping; its light samples; its
  // light's own point joined to the camera, about one), and what its light
  // subpath adds.
  const double samples = double(pilot.width) * double(pilot.height) * kPilotSpp;
  const size_t escaped = size_t(PathEnd::Escaped);
  const WaveStats& b = bdpt_stats;
  const double once = (samples + double(b.eye_vertices + b.eye_ends[escaped] + b.light_samples)) / samples;
  const double light = double(b.light_vertices + b.light_ends[escaped] + b.light_connections) / samples;
  // Under another choice of light, each light's rays scale with its rho.
  std::vector<RateArray> costs(lights.names.size());
  for (size_t c = 0; c < costs.size(); ++c) {
    double light_c = light;
    if (!ratios[c].empty()) {
      light_c = 0.0;
      for (size_t j = 0; j < light_rays.size(); ++j) light_c += double(ratios[c][j]) * light_rays[j] / samples;
    }
    for (size_t k = 0; k < kLightSubpathRates.size(); ++k) costs[c][k] = once + double(kLightSubpathRates[k]) * light_c;
  }
  pick_light_choice(moments, lights, costs, render.planned_spp, choice);
  if (lights.names.size() > 1 && choice.light_choice.empty()) {
    // Power stays: its rate from a pilot whose light subpaths it draws
    // (this one's, drawn otherwise, only estimate it), as on a scene of one
    // light; the candidates' estimates kept for --stats.
    LightSubpathRateChoice by_power =
        choose_light_subpath_rate(scene, light_sampler, render, backend, eye_alone, time_budget, false);
    by_power.light_choice_candidates = choice.light_choice_candidates;
    by_power.light_choice_error = choice.light_choice_error;
    by_power.light_choice_mse = choice.light_choice_mse;
    by_power.light_choice_cost = choice.light_choice_cost;
    return by_power;
  }
  if (eye_alone) {
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    consider_eye_subpaths_alone(scene, light_sampler, render, *eye_alone, backend, moments, once - 1.0,
                                seconds / samples, time_budget, choice);
  }
  choice.rate = best_light_subpath_rate(choice, render.planned_spp);
  return choice;
}

float best_light_subpath_rate(const LightSubpathRateChoice& c, uint32_t spp) {
  const float rate = best_light_subpath_rate(c.error, c.cost, spp);
  return c.eye_alone && eye_subpaths_alone_pay(*c.eye_alone, c.eye_alone_first_ratio) ? 0.f : rate;
}

namespace {
// --stats: a pilot's candidates and estimates.
void report_pilot(const LightSubpathRateChoice& c, RenderStats& stats) {
  if (!c.light_choice_candidates.empty()) {
    stats.light_choice = c.light_choice_name;
    stats.light_choice_probability.assign(c.light_choice.begin(), c.light_choice.end());
    stats.light_choice_candidates = c.light_choice_candidates;
    stats.light_choice_error = c.light_choice_error;
    stats.light_choice_mse = c.light_choice_mse;
    stats.light_choice_cost = c.light_choice_cost;
  }
  stats.light_subpath_candidates.assign(kLightSubpathRates.begin(), kLightSubpathRates.end());
  stats.light_subpath_error.assign(c.error.begin(), c.error.end());
  stats.light_subpath_cost.assign(c.cost.begin(), c.cost.end());
  if (c.eye_alone_error >= 0.0) {
    stats.light_subpath_candidates.push_back(0.0);
    stats.light_subpath_error.push_back(c.eye_alone_error);
    stats.light_subpath_cost.push_back(c.eye_alone_cost);
  }
}
}  // namespace

void set_light_subpath_rate(const Scene& scene, const LightSampler& light_sampler, const RenderOptions& opt,
                            const PathTracerSettings& eye_alone, BdptSettings& bs, RenderStats& stats,
                            const RenderHooks& hooks, const LightSubpathRateChoice* known) {
  // (Debug unit weights have no counts to rescale: rate 1.)
  if (opt.light_subpath_rate == kLightSubpathsAuto && !bs.unit_weights) {
    const bool choose_light = opt.light_choice == LightChoiceKind::Auto;
    const bool pilot = known || worth_a_rate_pilot(scene, bs, choose_light);
    LightSubpathRateChoice c;  // (no pilot: rate 1, light by power)
    if (known) {
      c = *known;
    } else if (pilot) {
      const bool alone = may_render_eye_subpaths_alone(scene, opt) && worth_a_grid_pilot(bs);
      c = choose_light_subpath_rate(scene, light_sampler, bs, opt.ray_backend, alone ? &eye_alone : nullptr,
                                    opt.time_limit_seconds, choose_light);
    }
    // (whether the grid pilot fits a time budget depends on the process's
    // clock, and vcm's choice may have been another process's: the
    // processes of one image take one's choice, each of them asked)
    agree_on(hooks, c.rate);
    agree_on(hooks, c.light_choice);
    bs.light_subpath_rate = c.rate;
    if (c.rate > 0.f) bs.light_choice = c.light_choice;
    if (pilot) report_pilot(c, stats);
  }
  stats.light_subpath_rate = bs.light_subpath_rate;
}

}  // namespace lantern
