// The light subpath rate q of bdpt (bdpt_mis.h), chosen per scene by
// measuring, before the render, what each candidate rate would cost and
// what error it would leave: the idea of Grittmann et al. 2022
// ("Efficiency-aware multiple importance sampling for bidirectional
// rendering algorithms"), here for the one parameter q.
//
// A pilot renders the camera's whole image at a low resolution with every
// camera sample tracing a light subpath (q = 1), and keeps each strategy's
// sample: its unweighted value U, its MIS weight and the part of the
// weight's ratio sum whose count class differs from its own. From those,
// each sample's weight at any other q follows (the counts are q for
// strategies that use the light subpath's vertices past the light, s >= 2,
// and 1 for the others), and so the second moment of a camera sample's
// estimate at q:
//   E[X^2] = E[A^2] + 2 E[A B] + E[B^2] / q
// where A sums the sample's strategies run once and B those run with
// probability q (weighted for q, not divided by it): with probability q
// the sample has A + B / q, otherwise A. Splats (t = 1) land in other
// pixels and count as their own samples. The per-pixel variances, relative
// to the pixel's value squared (plus the image's mean squared, which
// keeps the choice free of the image's scale), averaged over the image
// and times the cost per camera sample
// (rays: eye extensions, light samples and camera rays once, light
// extensions and connections of s >= 2 q times) give each candidate's
// error at equal time; the least wins, q = 1 unless another is at least
// 5% better (the pilot is small, and q = 1 is pbrt-v4's bdpt).
//
// Where every light can be hit by an eye subpath (area, infinite and
// volume lights: no point, spot or distant light, whose light only light
// subpaths carry through glass or mirrors), the eye subpaths alone are one
// more candidate, q = 0: the strategies s = 0 and s = 1 weighted against
// each other only, which is the path tracer (eye_subpaths_alone.h). This
// pilot estimates their error too (RateMoments::eye_alone_error), and a
// second pilot measures it at the image's own resolution where they may
// pay; when they do, bdpt renders with the path tracer's kernel.
//
// Covariances between strategies of different samples are left out, as
// in Grittmann et al. The pilot covers the whole image at the same seed
// whatever part of it a process renders, and its sums run in a fixed
// order, so every part, rank, thread count and resumed run chooses the
// same q.
#pragma once

#include <array>
#include <optional>
#include <string>
#include <vector>

#include "accel/ray_stream.h"
#include "film/film.h"
#include "integrator/bdpt.h"
#include "integrator/eye_subpaths_alone.h"
#include "integrator/path_tracer.h"
#include "integrator/wave.h"
#include "lantern/render.h"

namespace lantern {

class LightSampler;
struct Scene;

inline constexpr std::array<float, 4> kLightSubpathRates{1.f, 0.5f, 0.25f, 0.125f};

struct LightSubpathRateChoice {
  float rate = 1.f;  // 0: the eye subpaths alone (the path tracer)
  // Per candidate (kLightSubpathRates): the pilot image's estimated
  // relMSE per camera sample and the cost of a camera sample, in rays.
  std::array<double, kLightSubpathRates.size()> error{}, cost{};
  // The eye subpaths alone, when a candidate: the grid pilot's estimates
  // (eye_subpaths_alone.h), and this pilot's ratio of their error to
  // bdpt's at the best rate.
  std::optional<EyeAloneEstimate> eye_alone;
  double eye_alone_first_ratio = 0.0;
  // The eye subpaths alone in this pilot's units (the grid pilot's ratios
  // to bdpt at the best rate, times this pilot's figures for that rate):
  // for --stats. Error -1: not a candidate.
  double eye_alone_error = -1.0, eye_alone_cost = 0.0;
  // The light light subpaths start from (light_choice_pilot.h): the
  // winner's probability per light (empty: by power) and name; with
  // several lights, each candidate's name and error per camera sample at
  // its best rate (relMSE, and MSE over the image's mean squared), and its
  // cost in rays (error and cost above: the winner's).
  std::vector<float> light_choice;
  std::string light_choice_name = "power";
  std::vector<std::string> light_choice_candidates;
  std::vector<double> light_choice_error, light_choice_mse, light_choice_cost;
};


// A strategy's MIS weight had the light subpath rate been q rather than
// the rate it was computed at, from that weight and the part `rescaled`
// of its ratio sum of the other count class (bdpt_mis.h), at the rate 1.
float weight_at_rate(float weight, float rescaled, bool needs_light_subpath, float q, float mis_beta);

// The moments of a pilot's strategy samples (separate from the pilot's
// rendering so that tests can feed it records of their own).
//
// Besides the rates, it weighs other choices of the light a light subpath
// starts from (light_choice_pilot.h). A choice that gives light j the
// probability p'_j where the pilot's light subpaths had p_j scales the
// densities of the strategies s >= 2 of paths to light j by
// rho_j = p'_j / p_j: as a rate does, for those paths only. So a record of
// a path to light j is reweighed at the count q rho_j, a camera sample
// whose light subpath started at light i has the second moment
//   E[A^2] + 2 E[A B] + E[B^2] / (q rho_i)
// (B weighted at q rho_i), and its splats v^2 / (q rho_i).
class RateMoments {
 public:
  // stratified: the sampler lays out each pixel's numbers for the decision
  // to trace a light subpath stratified, so that a pixel's n samples trace
  // q n of them (the count's noise is left out). light_ratios: per choice
  // of light, rho per light (LightPools::all); an empty one, or a record
  // of no known light, has rho = 1: the pilot's own choice.
  // splat_share: the film's splat_square_share (its splats' squares are
  // counted times it).
  RateMoments(int width, int height, uint32_t spp, float mis_beta, bool stratified,
              std::vector<std::vector<float>> light_ratios = {{}}, double splat_share = 1.0);
  // A wave's records (the waves in a fixed order, so that the sums are the
  // same whatever the threads).
  void add(const WaveDesc& wave, const std::vector<StrategyRecord>& records);
  // Each rate's estimated relMSE of an image of one sample per pixel,
  // with light subpaths choosing their light by choice `choice`; or
  // (absolute) its MSE over the image's mean squared.
  std::array<double, kLightSubpathRates.size()> relative_error(size_t choice = 0, bool absolute = false) const;
  // The same for the eye subpaths alone (eye_subpaths_alone.h), from the
  // same records: the larger of their own samples' spread (strategies
  // s = 0 and s = 1 reweighed) and the second moment that every
  // strategy's samples estimate for them (eye_alone_density_ratio), which
  // sees the rare bright paths that their own samples miss.
  double eye_alone_error() const;

 private:
  void add_values(const std::vector<StrategyRecord>& records);
  void add_moments(const WaveDesc& wave, const std::vector<StrategyRecord>& records);
  void add_choice_moments(const WaveDesc& wave, const std::vector<StrategyRecord>& records, size_t choice);
  int pixel_of(const StrategyRecord& r) const;
  float weight_at(const StrategyRecord& r, float q) const {
    return weight_at_rate(r.weight, r.rescaled, r.s >= 2, q, beta_);
  }
  // A strategy of a light seen from the camera (s = 1, t = 1 or s = 0,
  // t = 2), whose ratio sum is all the other's: its weight at rho.
  float seen_weight(const StrategyRecord& r, float rho) const {
    return weight_at_rate(r.weight, r.weight > 0.f ? 1.f / r.weight - 1.f : 0.f, r.s == 1, rho, beta_);
  }
  float light_ratio(size_t choice, uint32_t light) const {
    const std::vector<float>& rho = ratios_[choice];
    return light < rho.size() ? rho[light] : 1.f;
  }
  size_t at(size_t choice, size_t pixel) const { return choice * value_.size() + pixel; }
  static constexpr size_t kRates = kLightSubpathRates.size();
  bool stratified_;
  int width_, height_;
  uint32_t spp_;
  float beta_;
  std::vector<std::vector<float>> ratios_;
  double splat_share_;
  // (1 / (the pixel's value squared + the image's mean squared), per pixel)
  // (absolute: 1 / the image's mean squared for every pixel)
  std::vector<double> relative_scale(bool absolute = false) const;
  std::vector<double> value_;  // per pixel: the sum of its weighted samples
  // per choice and pixel (at), per rate: camera samples' sum and sum of
  // squares, splats' sum of squares
  std::vector<std::array<double, kRates>> sum_, square_, light_sum_, splat_square_;
  std::vector<double> alone_sum_, alone_square_, alone_mis_;  // per pixel: the eye subpaths alone
};

// The candidate with the least error at equal cost, from the error and
// cost per camera sample of each (kLightSubpathRates; 1 unless another is
// at least 5% better). Not a rate below 1 / spp when the render plans spp
// samples per pixel (0: a time budget): a pixel would trace fewer than one
// light subpath, and the count noise the pilot takes as stratified away
// would not be.
// Then the eye subpaths alone, when a candidate, if they pay
// (eye_subpaths_alone_pay): 0.
float best_light_subpath_rate(const std::array<double, kLightSubpathRates.size()>& error,
                              const std::array<double, kLightSubpathRates.size()>& cost, uint32_t spp = 0);
float best_light_subpath_rate(const LightSubpathRateChoice& c, uint32_t spp);

// Renders the pilot for a bdpt render with `render`'s settings and chooses;
// with `eye_alone` (the path tracer's settings for the same render), that
// too is a candidate. time_budget: the render's, in seconds (0: none).
// With several lights and choose_light, the light light subpaths start
// from too (light_choice_pilot.h), unless `render` has a choice of its own.
LightSubpathRateChoice choose_light_subpath_rate(const Scene& scene, const LightSampler& light_sampler,
                                                 const BdptSettings& render, RayBackend backend,
                                                 const PathTracerSettings* eye_alone = nullptr,
                                                 double time_budget = 0.0, bool choose_light = true);

// Whether a render is large enough for the rate pilot: 16 times the
// pilot's camera samples (twice as many where it also chooses among
// several lights: choose_light) or more over the render's pixels, or a
// time budget, as for the grid pilot (eye_subpaths_alone.h). A smaller
// render keeps rate 1 and light subpaths that choose their light by
// power, pbrt-v4's bdpt: a pilot that costs more than a sixteenth of the
// render cannot save what it costs (the rates it chooses among win 5-30%
// at equal time).
bool worth_a_rate_pilot(const Scene& scene, const BdptSettings& render, bool choose_light = true);

// bs's rate: the options', or under auto the pilot's choice (`known`:
// already made, by vcm's merge pilot), which stats report with its
// estimates, or 1 where the render is too small for a pilot
// (worth_a_rate_pilot); the processes of one image take one's choice (`hooks`,
// integrator/agreement.h). A rate of 0 asks for the path tracer with
// `eye_alone`'s settings in bdpt's place.
void set_light_subpath_rate(const Scene& scene, const LightSampler& light_sampler, const RenderOptions& opt,
                            const PathTracerSettings& eye_alone, BdptSettings& bs, RenderStats& stats,
                            const RenderHooks& hooks, const LightSubpathRateChoice* known = nullptr);

}  // namespace lantern
