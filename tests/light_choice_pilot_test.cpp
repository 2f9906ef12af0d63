// How light subpaths choose their light (RenderOptions::light_choice,
// integrator/light_choice_pilot.h): every choice converges to the same
// image, the pilot predicts each choice's error, finds the light that
// matters where power hides it, and chooses the same whatever the threads.
#include "integrator/light_choice_pilot.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <string>

#include "guided_rooms.h"
#include "integrator/light_subpath_rate.h"
#include "integrator/render_settings.h"
#include "lantern/render.h"
#include "light/light_sampler.h"
#include "pilot_threads.h"
#include "sanitizer.h"
#include "scene/scene.h"
#include "stat_compare.h"

using namespace lantern;
using namespace lantern::guiding_test;

namespace {

// The room open to a white sky through a hole in its ceiling, with a lamp
// inside, of about a thirtieth of the sky's power (over the scene's
// bounding disk) while it lights much of what the camera sees: a bright
// ball, or (in_glass) a point light in a glass ball, whose light only
// light subpaths carry (next-event estimation cannot see it through the
// glass).
std::shared_ptr<Scene> sky_and_lamp(bool in_glass = true) {
  const std::string lamp = in_glass ? R"(
  LightSource "point" "rgb I" [ 0.5 0.5 0.5 ]
  Material "dielectric" "float eta" [ 1.5 ]
  Shape "sphere" "float radius" [ 0.15 ])"
                                    : R"(
  AreaLightSource "diffuse" "rgb L" [ 20 20 20 ]
  Shape "sphere" "float radius" [ 0.08 ])";
  return room(
      R"(Shape "trianglemesh" "point3 P" [ -2 2 -3  -2 2 -0.9  2 2 -0.9  2 2 -3 ] "integer indices" [ 0 1 2 0 2 3 ]
Shape "trianglemesh" "point3 P" [ -2 2 -0.1  -2 2 2  2 2 2  2 2 -0.1 ] "integer indices" [ 0 1 2 0 2 3 ]
Shape "trianglemesh" "point3 P" [ -2 2 -0.9  -2 2 -0.1  -0.4 2 -0.1  -0.4 2 -0.9 ] "integer indices" [ 0 1 2 0 2 3 ]
Shape "trianglemesh" "point3 P" [ 0.4 2 -0.9  0.4 2 -0.1  2 2 -0.1  2 2 -0.9 ] "integer indices" [ 0 1 2 0 2 3 ])",
      R"(LightSource "infinite" "rgb L" [ 0.5 0.5 0.5 ]
AttributeBegin
  Translate 1.2 1.6 1.2)" +
          lamp + R"(
AttributeEnd)",
      "sky-and-lamp.pbrt");
}

double probability_of(const std::vector<float>& p, size_t light) { return light < p.size() ? double(p[light]) : 0.0; }

}  // namespace

// The same means whichever light the light subpaths choose: region means
// over independent renders, uniform against by power, within 4.5 standard
// errors, with either lamp. With the MIS densities by power while the
// light subpaths choose uniformly (emission_pdf, area_emission_pdf and
// infinite_emission_pdf reading LightPools::selection), the room with the
// bright ball is 130 standard errors off at 32 samples a run (checked;
// about 90 at the 16 here, z going with the square root of the samples). (The lamp in glass
// does not see it: its paths have strategies s >= 2 only, whose weights
// do not depend on the light's probability.)
TEST(LightSubpathChoice, BdptConvergesToTheSameImageWhateverTheChoice) {
  if (LANTERN_ASAN) GTEST_SKIP() << "statistics only: the Release suite runs it";
  std::vector<Region> regions;
  for (int y = 0; y < 32; y += 8)
    for (int x = 0; x < 32; x += 8) regions.push_back({x, y, 8, 8});
  for (const bool in_glass : {false, true}) {
    const auto scene = sky_and_lamp(in_glass);
    const std::vector<float> power = power_choice(scene->lights);
    ASSERT_EQ(power.size(), 2u);
    EXPECT_GT(std::max(power[0], power[1]), 20.f * std::min(power[0], power[1]));  // (what makes the choice matter)
    RenderOptions o = bdpt_options(1.f);
    o.spp = 16;
    o.light_choice = LightChoiceKind::Power;
    const RegionStats by_power = stats_of(render_runs(*scene, o, 12, 300), regions);
    o.light_choice = LightChoiceKind::Uniform;
    const RegionStats uniform = stats_of(render_runs(*scene, o, 12, 400), regions);
    print_z(in_glass ? "uniform against power, lamp in glass" : "uniform against power", max_z_of(by_power, uniform));
    expect_means_agree(by_power, uniform, 0.0,
                       in_glass ? "uniform light choice, lamp in glass" : "uniform light choice");
  }
}

// The pilot's estimate of each candidate's error per camera sample, as a
// ratio to power's, against the variance measured over 48 renders of 8
// samples at the pilot's own resolution: uniform within 15%. (A render of
// one planned sample per pixel keeps every candidate at rate 1.) Without
// the ratio rho in the weights and the second moment (each candidate
// weighed as the pilot's own choice) it predicts 1.0; with the pilot's
// light subpaths chosen by power, from whose few lamp subpaths uniform's
// error must be extrapolated, 0.37; without the splats' share of the
// filter (splat_square_share), 0.12 (all checked, against 0.18 measured).
TEST(LightSubpathChoice, PilotPredictsTheErrorOfEachChoice) {
  if (LANTERN_ASAN) GTEST_SKIP() << "statistics only: the Release suite runs it";
  const auto scene = sky_and_lamp();
  const LightSampler light_sampler(scene->lights, scene->shapes, scene->textures, LightSamplerKind::Bvh);
  RenderOptions o = bdpt_options(1.f);
  o.width = o.height = 64;
  o.spp = 8;
  double predicted = 0.0;
  constexpr int kPilots = 8;
  for (int seed = 0; seed < kPilots; ++seed) {  // (one pilot is noisy: their mean)
    o.seed = uint64_t(seed);
    BdptSettings bs = bdpt_settings(*scene, o, image_region(*scene, o), 1);
    const LightSubpathRateChoice c = choose_light_subpath_rate(*scene, light_sampler, bs, RayBackend::StreamNp);
    ASSERT_EQ(c.light_choice_candidates.size(), 4u);
    ASSERT_EQ(c.light_choice_candidates[1], "uniform");
    predicted += c.light_choice_error[1] / c.light_choice_error[0] / kPilots;
  }
  o.light_choice = LightChoiceKind::Power;
  const double by_power = relative_variance_of(render_runs(*scene, o, 48, 500), o.spp);
  o.light_choice = LightChoiceKind::Uniform;
  const double measured = relative_variance_of(render_runs(*scene, o, 48, 500), o.spp) / by_power;
  std::printf("  uniform's error over power's: predicted %.3f, measured %.3f\n", predicted, measured);
  EXPECT_NEAR(predicted / measured, 1.0, 0.15);
  EXPECT_LT(measured, 0.9);  // (the choice matters here)
}

// The prism: the sky's power is about 1,900 times the spot's, whose light
// subpaths alone draw the beam. The pilot gives the spot a large share,
// and estimates power's error at equal cost at more than twice the
// winner's. Weighing the candidates as the pilot's own choice (rho = 1),
// or drawing the pilot's light subpaths by power, fails (checked).
TEST(LightSubpathChoice, PilotFindsTheLightThatMatters) {
  const auto scene = load_scene(std::string(LANTERN_SOURCE_DIR) + "/scenes/prism.pbrt");
  const LightSampler light_sampler(scene->lights, scene->shapes, scene->textures, LightSamplerKind::Bvh);
  RenderOptions o = bdpt_options(kLightSubpathsAuto);
  o.width = 96;
  o.height = 72;
  o.spectral = true;
  const BdptSettings bs = bdpt_settings(*scene, o, image_region(*scene, o), 0);
  const LightSubpathRateChoice c = choose_light_subpath_rate(*scene, light_sampler, bs, RayBackend::StreamNp);
  const std::vector<float> power = power_choice(scene->lights);
  const size_t spot = power[0] < power[1] ? 0 : 1;
  EXPECT_LT(power[spot], 0.002f);
  ASSERT_FALSE(c.light_choice.empty()) << "kept " << c.light_choice_name;
  std::printf("  the spot's share: %.3f (%s)\n", probability_of(c.light_choice, spot), c.light_choice_name.c_str());
  EXPECT_GT(probability_of(c.light_choice, spot), 0.2) << c.light_choice_name;
  // Power's relMSE and MSE at equal cost are well above the winner's.
  ASSERT_EQ(c.light_choice_mse.size(), c.light_choice_candidates.size());
  double winner = 0.0, winner_mse = 0.0;
  for (size_t k = 0; k < c.light_choice_candidates.size(); ++k)
    if (c.light_choice_candidates[k] == c.light_choice_name) {
      winner = c.light_choice_error[k] * c.light_choice_cost[k];
      winner_mse = c.light_choice_mse[k] * c.light_choice_cost[k];
    }
  EXPECT_LT(winner, 0.5 * c.light_choice_error[0] * c.light_choice_cost[0]);
  EXPECT_LT(winner_mse, 0.5 * c.light_choice_mse[0] * c.light_choice_cost[0]);
}

// Every thread count makes the same choice, and a scene of one light, or a
// render that asks for power, has none to make.
TEST(LightSubpathChoice, PilotIsTheSameWhateverTheThreads) {
  const auto scene = sky_and_lamp();
  const RenderOptions o = bdpt_options(kLightSubpathsAuto);
  const auto [one, two] = pilots_on_one_and_all_threads(*scene, o);
  EXPECT_EQ(one.light_choice_name, two.light_choice_name);
  EXPECT_EQ(one.light_choice, two.light_choice);
  EXPECT_EQ(one.light_choice_error, two.light_choice_error);
  EXPECT_EQ(one.rate, two.rate);

  const LightSampler light_sampler(scene->lights, scene->shapes, scene->textures, LightSamplerKind::Bvh);
  const LightSubpathRateChoice none =
      choose_light_subpath_rate(*scene, light_sampler, bdpt_settings(*scene, o, image_region(*scene, o), 0),
                                RayBackend::StreamNp, nullptr, 0.0, false);
  EXPECT_TRUE(none.light_choice.empty());
  EXPECT_TRUE(none.light_choice_candidates.empty());
  const LightSubpathRateChoice single = pilots_on_one_and_all_threads(*guided_room(), o).first;
  EXPECT_TRUE(single.light_choice.empty());
  EXPECT_TRUE(single.light_choice_candidates.empty());
}

// The render reports the choice under auto with several lights, and
// refuses an unknown one.
TEST(LightSubpathChoice, RenderReportsItsChoice) {
  const auto scene = sky_and_lamp();
  RenderOptions o = bdpt_options(kLightSubpathsAuto);
  o.time_limit_seconds = 0.01;  // (a time budget: the pilot runs whatever the render's size)
  RenderResult r = render(*scene, o);
  EXPECT_FALSE(r.stats.light_choice.empty());
  EXPECT_EQ(r.stats.light_choice_candidates.size(), 4u);
  EXPECT_EQ(r.stats.light_choice_error.size(), 4u);
  EXPECT_EQ(r.stats.light_choice_mse.size(), 4u);
  o.light_choice = LightChoiceKind::Power;
  r = render(*scene, o);
  EXPECT_TRUE(r.stats.light_choice.empty());
  EXPECT_EQ(parse_light_choice("uniform"), LightChoiceKind::Uniform);
  for (const char* bad : {"", "Power", "bvh", "uniform "})
    EXPECT_THROW(parse_light_choice(bad), std::invalid_argument) << bad;
}

// Candidates: power first, uniform over the lights with power, and the
// mixtures keep a light without power out and every other light in.
TEST(LightSubpathChoice, CandidatesKeepEveryLightThatEmits) {
  const LightChoices c = light_choice_candidates({0.7f, 0.3f, 0.f}, {0.0, 1.0, 0.0});
  ASSERT_EQ(c.names.size(), 4u);
  EXPECT_EQ(c.names[0], "power");
  EXPECT_EQ(c.probabilities[1], (std::vector<float>{0.5f, 0.5f, 0.f}));
  EXPECT_FLOAT_EQ(c.probabilities[2][0], 0.35f);
  EXPECT_FLOAT_EQ(c.probabilities[2][1], 0.65f);
  EXPECT_FLOAT_EQ(c.probabilities[3][0], 0.07f);
  EXPECT_EQ(c.probabilities[3][2], 0.f);
  // Nothing measured: the mixtures are power.
  const LightChoices none = light_choice_candidates({0.7f, 0.3f}, {0.0, 0.0});
  EXPECT_EQ(none.probabilities[3], none.probabilities[0]);
  const std::vector<std::vector<float>> rho = light_choice_ratios(c, {0.5f, 0.5f, 0.f});
  EXPECT_FLOAT_EQ(rho[0][0], 1.4f);
  EXPECT_FLOAT_EQ(rho[0][2], 1.f);  // (no light subpath starts there either way)
}
