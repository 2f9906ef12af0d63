// Which light a bdpt light subpath starts from (BdptSettings::light_choice),
// chosen per scene by the light subpath rate's pilot (light_subpath_rate.h).
//
// pbrt-v4's bdpt chooses by power, and so does Lantern by default. Where
// the lights' powers and what they bring to the image disagree, that
// starves the light that matters: a sky of a thousand times a spot's power
// takes all but one light subpath in a thousand, while only the spot's
// light subpaths draw its beam through a prism (caustics that no eye
// subpath can find). Every strategy stays weighted by MIS with the density
// its light subpath was drawn with, so any choice that gives every light
// with power a probability above zero leaves the image unbiased; the
// choice only moves noise.
//
// The candidates (LightChoices): by power; uniform; and two mixtures of
// power with a target measured by a short first pass. That pass renders
// the pilot's image with light subpaths choosing half by power and half
// uniformly (so that every light has light subpaths), and sums for each
// light j the squares S_j of what its light subpaths' strategies
// (s >= 2) bring to each camera sample. With n_j = N p_j of the N samples
// from light j, the second moment of those strategies at a choice p'
// (their weights held) is sum_j E[B^(1)_j^2] / p'_j, where B^(1) is a
// sample's value times p_j; it is least at p'_j proportional to
// sqrt(E[B^(1)_j^2]) = sqrt(p_j S_j / N): the target. The mixtures keep a
// share by power, so that a light the first pass missed keeps light
// subpaths.
//
// The pilot then weighs each candidate with its records (RateMoments:
// the MIS weights at each candidate's densities) and its cost (each
// light's rays per light subpath, weighed by the candidate's
// probabilities). A candidate wins if it raises neither relMSE nor MSE at
// equal cost above power's and lowers one of them by 30%
// (light_subpath_rate.cpp, pick_light_choice).
#pragma once

#include <string>
#include <vector>

#include "accel/ray_stream.h"
#include "integrator/bdpt.h"

namespace lantern {

class LightSampler;
struct Scene;

struct LightChoices {
  std::vector<std::string> names;                 // "power" first
  std::vector<std::vector<float>> probabilities;  // per candidate, per light (LightPools::all)
};

// The lights' probabilities by power (LightPools::selection).
std::vector<float> power_choice(const LightPools& lights);
// Uniform over the lights with power (RenderOptions::light_choice).
std::vector<float> uniform_choice(const LightPools& lights);
// The first pass's choice: half by power, half uniform.
std::vector<float> first_pass_choice(const LightPools& lights);

// The first pass: `pilot` (its light_choice set, first_pass_choice)
// rendered for `spp` samples of each pixel; the target per light (summing
// to 1; all zero when no light subpath brought anything).
std::vector<double> light_choice_target(const Scene& scene, const LightSampler& light_sampler,
                                        const BdptSettings& pilot, uint32_t spp, RayBackend backend);

// The candidates from the lights' powers and the target.
LightChoices light_choice_candidates(const std::vector<float>& power, const std::vector<double>& target);

// Per candidate, the ratio of its probability to `pilot`'s for each light
// (RateMoments' light_ratios).
std::vector<std::vector<float>> light_choice_ratios(const LightChoices& choices, const std::vector<float>& pilot);

}  // namespace lantern
