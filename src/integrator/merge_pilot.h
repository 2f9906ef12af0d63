// Whether vcm's merges pay for what they cost, measured before the render:
// vcm renders as bdpt where they do not (docs/vcm.md, "Merges that pay").
//
// Merging costs every camera sample a range query at each eye vertex and
// every wave a grid of its light vertices: vcm draws 0.68 to 0.87 of
// bdpt's samples per second at equal rays. Where connections already
// carry the light (a Cornell box, a door ajar), merges take some of each
// path's weight and add little; where no connection can sample a path
// (a caustic seen through water from a small light) they are the only
// strategy that renders it. The pilot estimates both
// renders' error at equal time on the grid pilot's pixels
// (eye_subpaths_alone.h): bdpt as it would render (its light subpath rate
// and choice of light, or the eye subpaths alone), and vcm, whose camera
// samples must merge with as many light subpaths as the render's waves
// hold. So the vcm pilot traces, per pass, one wave of the render's size
// (every light subpath, camera samples only at the grid's pixels,
// WaveDesc::eye_pixels), a few passes with each of two seeds; a pixel's
// variance is half the squared difference of the two seeds' means plus
// the second moment of the splats its cell receives.
//
// The estimates are sums in a fixed order over a pilot of the whole image
// at seeds of its own, so every part, rank and thread count makes the
// same choice (for a time budget, see choose_merging). A scene that asks
// for photon mapping keeps its merges.
#pragma once

#include <cstdint>
#include <optional>

#include "integrator/bdpt.h"
#include "integrator/eye_subpaths_alone.h"
#include "integrator/light_subpath_rate.h"
#include "integrator/path_tracer.h"
#include "integrator/render_settings.h"
#include "lantern/render.h"

namespace lantern {

class LightSampler;
struct Scene;

struct MergeEstimate {
  // relMSE per camera sample (as EyeAloneMoments) and its cost in rays
  double vcm_error = 0.0, vcm_cost = 0.0;
  double bdpt_error = 0.0, bdpt_cost = 0.0;  // bdpt as it would render
  double missed = 0.0;                       // of bdpt_error, missed_light_error's
  // The vcm pilot's wall seconds per path it traced (camera and light):
  // for a time budget's check of the pilots' time only.
  double seconds_per_path = 0.0;
};

// What bdpt's error lacks where its pilot missed light that vcm's found:
// a pixel whose vcm mean exceeds bdpt's by d (beyond kMissedLightZ
// standard errors of the difference) holds paths that none of bdpt's N
// camera samples there found. Their probability per sample is then
// about 1 / N or less, and a sample that finds one brings d / p: a
// variance of d^2 N or more per sample. Summed over the grid as relMSE
// per camera sample. (On the pool at 240 x 180, whose floor's caustics
// only merges sample well, it is 2.1 of bdpt's estimated 3.0.)
inline constexpr double kMissedLightZ = 3.0;
double missed_light_error(const GridMeans& vcm, const GridMeans& bdpt);

// Merges stay unless bdpt's error times cost is below kMergesClearGain of
// vcm's: a pilot sees few of the rare bright paths that merges take from
// bdpt's strategies, so bdpt must win clearly.
inline constexpr double kMergesClearGain = 0.8;
bool merges_pay(const MergeEstimate& e);

// vcm's time per ray over bdpt's at equal rays (the grids, a range query
// at every eye vertex, the larger MIS sums, waves of more light
// subpaths): 1.15 to 1.48 on six shipped scenes rendered for 10 s; and a
// merge's cost in rays' time (docs/vcm.md, "Merges that pay").
inline constexpr double kVcmRayFactor = 1.3, kMergeRays = 0.8;

// The vcm pilot's passes per seed.
inline constexpr uint32_t kMergePilotPasses = 8;
inline constexpr double kMergePilotLeastBudget = 2.0;

// Whether a vcm render is large enough for the pilot: its samples at
// least 16 times the pilot's light subpaths (a time budget: see
// choose_merging, and at least kMergePilotLeastBudget seconds, where the
// pilot's first wave, which tells whether the rest fits, costs little).
bool worth_a_merge_pilot(const BdptSettings& vcm, uint32_t wave_paths);

// vcm's side of the estimate: `vcm` the render's settings, wave_paths the
// light subpaths of its waves. False: not measured (an image too small,
// or a time budget too short for the pilot).
bool estimate_vcm(const Scene& scene, const LightSampler& light_sampler, const BdptSettings& vcm, uint32_t wave_paths,
                  RayBackend backend, double time_budget, MergeEstimate& e, GridMeans& means);

struct MergingChoice {
  bool merge = true;
  std::optional<MergeEstimate> estimate;  // when the pilot ran
  // bdpt's own pilot's choice (light_subpath_rate.h), which a render
  // without merges takes as it is
  std::optional<LightSubpathRateChoice> bdpt;
  bool from_checkpoint = false;  // a resumed render's: as its checkpoint was made
};

// For a vcm render with RenderOptions::merging_pilot large enough to be
// worth it, runs bdpt's pilots and vcm's, and says whether to merge.
// Under a time budget the pilots are not run when they would take more
// than a sixteenth of the budget at the time the first wave took: the one
// choice that depends on time, as the grid pilot's (light_subpath_rate.h).
// Processes that render one image must choose alike: MPI's ranks take the
// choice of the one that reads the checkpoint (`agreed`: RenderHooks::
// agree is set, agree_on below), which goes on as the checkpoint was made
// when it resumes one; --part's parts cannot, so under a time budget they
// run no pilot and merge.
MergingChoice choose_merging(const Scene& scene, const LightSampler& light_sampler, const RenderOptions& opt,
                             const ImageRegion& region, uint32_t planned_spp, bool agreed = false);
// The choice of the process that reads the checkpoint, where hooks.agree
// says it (a collective call: every process makes it); this process's
// estimates are dropped where it chose otherwise.
void agree_on(const RenderHooks& hooks, MergingChoice& choice);
// The options a render runs with: the asked ones, or bdpt's if merges do
// not pay (and bdpt's waves, unless --wave-size asked for others).
RenderOptions rendered_as(const RenderOptions& asked, const MergingChoice& choice, const Scene& scene);
// --stats: the choice, and the pilot's estimates; `seconds` the pilots'.
void report_merging(const MergingChoice& choice, double seconds, RenderStats& stats);

}  // namespace lantern
