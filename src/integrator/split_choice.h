// `--split auto`: the paths per camera sample of the path tracer
// (PathTracerSettings::split), chosen per scene by a pilot that measures
// each candidate's error at equal time, as the splitting factors of Vorba
// and Křivánek 2016 ("Adjoint-driven Russian roulette and splitting") and
// Rath et al. 2022 ("EARS") follow from variance and cost.
//
// The pilot renders about 4,096 pixels spread over the image (every
// stride-th pixel of every stride-th row, at the image's own resolution:
// at a lower one a pixel holds more of the scene, and splitting looks
// worse), 32 paths each, with each candidate and two seeds (the same two
// for both). Half the squared difference of a candidate's two images is
// its variance, measured with its own sample numbers: a split camera
// sample's next-event estimate is stratified across the pixel's camera
// samples, which a model of independent samples would miss (one predicted
// 1.1 times the error of whole camera samples in the Cornell box, where
// splitting by 4 leaves 0.88). Each pixel weighs as relative to its value
// squared plus the image's mean squared, its value the mean of every
// candidate's images there (split_choice.cpp). The cost of a path split k ways is a / k + 1 - a
// of a whole camera sample's, with a = 0.5 / v the share of its work done
// once per camera sample, v the surface vertices of a path: measured at
// equal settings, a was 0.17 in the Cornell box's paths of 2.67 vertices
// and 0.40 in the lamp-lit street's of 1.2 (docs/splitting.md). A
// candidate other than 1 must leave at most kSplitGain of 1's error: the
// pilot is small.
//
// The pilot covers the film's pixels (a crop's, with one: every process of
// a render has the same film, and shares its waves) at the same seed, and
// sums in a fixed order: every part, rank, thread count and resumed run
// chooses the same.
#pragma once

#include <array>
#include <cstdint>

#include "integrator/path_tracer.h"
#include "lantern/render.h"

namespace lantern {

class LightSampler;
struct Scene;

inline constexpr std::array<uint32_t, 2> kSplitCandidates = {1, 4};
inline constexpr double kSplitGain = 0.98;

struct SplitChoice {
  uint32_t split = 1;
  std::array<double, kSplitCandidates.size()> variance{};  // relative, summed over the pilot's pixels
  double camera_share = 0.0;                               // a
  std::array<double, kSplitCandidates.size()> error{};     // at equal time, relative to 1's
};

// The candidate with the least error at equal time from the measured
// variances and a.
SplitChoice best_split(const std::array<double, kSplitCandidates.size()>& variance, double camera_share);

// Runs the pilot for a render with `render`'s settings (its split is
// ignored).
SplitChoice choose_split(const Scene& scene, const LightSampler& light_sampler, const PathTracerSettings& render,
                         RayBackend backend);

// kSplitAuto in `render`: the pilot's choice, or 1 for a render too small to
// be worth the pilot; the pilot's estimates into `stats`. The processes of
// one image take one's choice (`hooks`, integrator/agreement.h).
void set_split(const Scene& scene, const LightSampler& light_sampler, const RenderOptions& opt,
               PathTracerSettings& render, RenderStats& stats, const RenderHooks& hooks);

// Whether a render is worth the pilot (about 520,000 paths): 16 times as
// many paths, or a time budget of 8 seconds or more (the pilot takes
// 0.2 s of the Cornell box's).
bool worth_a_split_pilot(const PathTracerSettings& render, double time_budget);

}  // namespace lantern
