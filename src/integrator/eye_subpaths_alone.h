// bdpt without light subpaths: the eye subpaths alone, with their
// strategies s = 0 (emission found) and s = 1 (next-event estimation)
// weighted against each other only. That is the path tracer, which bdpt
// renders with when its pilot (light_subpath_rate.h) finds that light
// subpaths do not pay for what they cost.
//
// Whether they pay turns on what the rate pilot (8 samples per pixel at
// a sixteenth of the image's pixels) cannot see: the path tracer's error
// per sample falls with the samples per pixel and grows with the pixel's
// footprint far more than bdpt's (a Cornell box, relMSE per sample of
// path over bdpt at q = 1: 2.8 at 64 x 64 and 8 samples, 1.6 at 256 x 256
// and 64), because the sampler stratifies its first bounces across a
// pixel's samples. So a grid pilot takes about 512 pixels of the image at
// its own resolution (every stride-th in x and y), 64 samples each, twice
// with two seeds, with bdpt at the chosen rate and with the path tracer,
// and measures the variance of each pixel's mean as half the squared
// difference of the two seeds' means, which holds the stratification.
//
// A pilot this small sees the rare bright paths of the path tracer (a
// small light's caustics) now and then. So the rate pilot also estimates
// its error from what bdpt's strategies sample of those paths
// (eye_alone_density_ratio), and the eye subpaths alone are chosen only
// where the two pilots agree (eye_subpaths_alone_pay).
#pragma once

#include <algorithm>
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "film/film.h"
#include "integrator/bdpt.h"
#include "integrator/path_tracer.h"
#include "integrator/wave.h"
#include "lantern/render.h"

namespace lantern {

class LightSampler;
struct Scene;

// Whether a bdpt render may run with the eye subpaths alone: they must
// reach all the light: no point, spot or distant light where a material
// may be specular (material/may_be_specular.h), since only light subpaths
// carry their light through glass or off mirrors. So they render the same
// image, and nothing be asked of bdpt that the path tracer does not do
// (per-strategy images, unit weights, guided light subpaths, the balance
// heuristic).
bool may_render_eye_subpaths_alone(const Scene& scene, const RenderOptions& opt);
std::string why_not_eye_subpaths_alone(const Scene& scene, const RenderOptions& opt);  // ("": it may)

// A record's weight with the eye subpaths alone: s = 0 and s = 1 weighed
// against each other only; the light seen from the camera (s = 0, t = 2)
// has no other strategy left (s = 1, t = 1 joins a light subpath's first
// vertex to the camera). 0 for the strategies that need a light subpath.
float eye_alone_weight(const StrategyRecord& r, float mis_beta);

// The second moment of the eye subpaths alone, estimated from bdpt's
// samples of every strategy: over the paths of a strategy k of density
// p_k, the alone estimator's f^2 sum over its strategies i of w_i^2 / p_i
// is w_k U^2 (p_k sum_i w_i^2 / p_i), U = f / p_k, weighted by bdpt's
// w_k (an MIS estimate of that integral: Veach 1997, eq. 9.7). This is
// the factor p_k sum_i w_i^2 / p_i for a record, from its weight's ratio
// sums (power heuristic): 1 / sqrt of the eye strategies' share for a
// strategy that needs a light subpath (one eye strategy dominant: an
// upper estimate, at most 1.42 times the true one when two share it).
// Paths the eye subpaths sample seldom (caustics of small lights, seen
// through or on glass) are sampled often by light subpaths, so this sees
// their share of the alone estimator's variance where its own samples, as
// few as a pilot's, would mostly miss it.
double eye_alone_density_ratio(const StrategyRecord& r);

// The grid pilot's pixels: every stride-th of a width x height image in x
// and y, from stride / 2, each standing for its cell of stride x stride
// pixels (the last row and column of cells take what the image has left).
struct PilotGrid {
  PilotGrid(int width, int height, int stride);
  int grid_index(int x, int y) const;  // -1: not on the grid
  int grid_index(uint32_t pixel) const {
    return grid_index(int(pixel % uint32_t(width)), int(pixel / uint32_t(width)));
  }
  int cell_index(int x, int y) const;  // the grid pixel whose cell holds pixel (x, y); -1: outside
  int width, height, stride, columns;
  std::vector<uint32_t> pixels;
};

// Per pixel of a grid pilot: an estimator's mean and the variance of that
// mean (the merge pilot compares bdpt's with vcm's: merge_pilot.h).
struct GridMeans {
  std::vector<double> mean, variance;
  double samples = 0.0;  // camera samples per pixel
};
// The variance of a pixel's mean of n samples, from their sum and the sum
// of their squares (the samples' spread: a stratified sampler's mean has
// less), plus its splats' second moment summed over the n.
inline double grid_mean_variance(double sum, double square, double n, double splat_square) {
  const double spread = std::max(0.0, square - sum * sum / n) / (n - 1.0);
  return (spread + splat_square / n) / n;
}

// The pilot's sums: per pixel of the grid and seed, the mean of bdpt at
// rate q (its camera samples, the light subpath's share weighted for q but
// not divided by it: the coin that decides whether a sample traces one is
// added as a variance of its own) and of the eye subpaths alone; and the
// splats' second moments.
class EyeAloneMoments {
 public:
  // grid: the pilot's pixels, every stride-th of a width x height image.
  // stratified: as RateMoments.
  EyeAloneMoments(int width, int height, int stride, uint32_t spp, float q, float mis_beta, bool stratified);
  const std::vector<uint32_t>& pixels() const { return grid_.pixels; }
  // bdpt's records of a wave at rate 1 (seed 0 or 1; first: the index in
  // pixels() of the wave's first pixel), the path tracer's samples.
  void add_bdpt(int seed, size_t first, const WaveDesc& wave, const std::vector<StrategyRecord>& records);
  void add_alone(int seed, const std::vector<FilmSample>& samples);
  // relMSE per camera sample (the variance of a pixel's mean relative to
  // its value squared plus the image's mean squared, times spp): bdpt at q
  // and the eye subpaths alone.
  std::array<double, 2> relative_error() const;
  // bdpt's mean per pixel of the grid and its variance, from the
  // samples' spread (which a stratified sampler's mean has less of).
  GridMeans bdpt_means() const;

 private:
  PilotGrid grid_;
  uint32_t spp_;
  float q_, beta_;
  bool stratified_;
  // per grid pixel: per seed, the sums of bdpt's samples, of the eye
  // subpaths' alone and of the light subpath's share; over both seeds, the
  // light subpath's share squared (the coin's), the pixel's value at q = 1
  // and the splats' second moment
  std::vector<std::array<double, 2>> bdpt_, alone_, light_;
  std::vector<double> coin_, value_, splat_square_;
  std::vector<double> sample_sum_, sample_square_;  // bdpt's camera samples at rate 1, over both seeds
};

struct EyeAloneEstimate {
  double bdpt_error = 0.0, alone_error = 0.0;  // relMSE per camera sample
  double bdpt_cost = 0.0, alone_cost = 0.0;    // per camera sample, in rays
  GridMeans bdpt_means;                        // at rate 1, splats included
};

// Whether the eye subpaths alone pay: their error times their cost at
// least 5% below bdpt's, both as the grid pilot measured them, and the
// rate pilot agreeing on how their errors compare (its ratio of the eye
// subpaths' error alone to bdpt's, `first_ratio`, within a factor 4 of the
// grid pilot's). That pilot sees all of the image, the grid a sixteenth
// of a pixel in 16 (at 256 x 256): a disagreement is rare bright paths that
// one of them saw and the other missed, and then light subpaths stay.
bool eye_subpaths_alone_pay(const EyeAloneEstimate& e, double first_ratio);
inline constexpr double kPilotsAgree = 4.0, kClearGain = 0.95;

// Whether a render is large enough for the grid pilot: 16 times its
// camera samples (grid_pilot_samples, half of them bdpt's) or more over
// the render's pixels (a crop window's; every part's and MPI rank's whole
// image), or a time budget (for which the rate pilot's time
// decides: light_subpath_rate.cpp). Smaller renders keep light subpaths:
// the pilot would cost more than it could save.
bool worth_a_grid_pilot(const BdptSettings& render);
double grid_pilot_samples();
// The grid's pixels: every stride-th in x and y, about 512 of them.
int grid_pilot_stride(int width, int height);

// Runs the pilot for a bdpt render with `render`'s settings: bdpt at rate
// q against the eye subpaths alone with Russian roulette scaled by
// eye_roulette (the path tracer's); with_alone false: bdpt's side only
// (the merge pilot's, merge_pilot.h, for a bdpt that keeps light subpaths).
EyeAloneEstimate estimate_eye_subpaths_alone(const Scene& scene, const LightSampler& light_sampler,
                                             const BdptSettings& render, float q, const PathTracerSettings& eye_alone,
                                             RayBackend backend, bool with_alone = true);

}  // namespace lantern
