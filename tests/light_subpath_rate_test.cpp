// bdpt's light subpath rate (RenderOptions::light_subpath_rate): images
// that converge to the same means at every rate, a pilot whose predicted
// errors follow the measured ones, and a choice that is the same whatever
// the threads.
#include "integrator/light_subpath_rate.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "guided_rooms.h"
#include "integrator/render_settings.h"
#include "lantern/render.h"
#include "light/light_sampler.h"
#include "pilot_threads.h"
#include "sanitizer.h"
#include "scene/scene.h"
#include "stat_compare.h"

using namespace lantern;
using namespace lantern::guiding_test;

// The same means at every rate, on surfaces (a closed room with a small
// light) and in a fog lit through a hole: region means over independent
// renders agree within 4.5 standard errors with every camera sample
// tracing a light subpath. Without the counts in the weights (a light
// subpath's strategies weighted as if every sample had one), or without
// dividing by q, they are many standard errors off (checked).
TEST(LightSubpaths, BdptConvergesToTheSameImageAtEveryRate) {
  if (LANTERN_ASAN) GTEST_SKIP() << "statistics only: the Release suite runs it";
  std::vector<Region> regions;
  for (int y = 0; y < 32; y += 8)
    for (int x = 0; x < 32; x += 8) regions.push_back({x, y, 8, 8});
  for (const auto& scene : {guided_room(), foggy_skylit_room()}) {
    RenderOptions o = bdpt_options(1.f);
    o.spp = 32;
    const RegionStats every = stats_of(render_runs(*scene, o, 12, 300), regions);
    for (const float q : {0.5f, 0.2f}) {
      o.light_subpath_rate = q;
      const RegionStats some = stats_of(render_runs(*scene, o, 12, 400), regions);
      max_z(every, some);
      expect_means_agree(every, some, 0.0, ("light subpath rate " + std::to_string(q)).c_str());
    }
  }
}

// The pilot's estimates of each rate's error per camera sample, as ratios
// to rate 1's, against the variance measured over 24 renders of 8 samples
// at the pilot's own resolution (the Cornell box at 64 x 64): within 10%
// (measured: 2-4% above, over 24 and over 48 renders). Leaving out the 1 / q of the light subpath's
// strategies (E[B^2] instead of E[B^2] / q) predicts 11-16% too little
// and fails (checked).
TEST(LightSubpaths, PilotPredictsTheErrorOfEachRate) {
  if (LANTERN_ASAN) GTEST_SKIP() << "statistics only: the Release suite runs it";
  const auto scene = load_scene(std::string(LANTERN_SOURCE_DIR) + "/scenes/cornell-box.pbrt");
  const LightSampler light_sampler(scene->lights, scene->shapes, scene->textures, LightSamplerKind::Bvh);
  RenderOptions o = bdpt_options(1.f);
  o.width = o.height = 64;
  o.maxdepth = 10;
  o.spp = 8;
  std::array<double, kLightSubpathRates.size()> predicted{};
  constexpr int kPilots = 8;
  for (int seed = 0; seed < kPilots; ++seed) {  // (one pilot is noisy: their mean)
    o.seed = uint64_t(seed);
    const BdptSettings bs = bdpt_settings(*scene, o, image_region(*scene, o), 0);
    const LightSubpathRateChoice c = choose_light_subpath_rate(*scene, light_sampler, bs, RayBackend::StreamNp);
    for (size_t k = 0; k < predicted.size(); ++k) predicted[k] += c.error[k] / c.error[0] / kPilots;
  }
  const double at_one = relative_variance_of(render_runs(*scene, o, 24, 500), o.spp);
  for (size_t k = 1; k < kLightSubpathRates.size(); ++k) {
    o.light_subpath_rate = kLightSubpathRates[k];
    const double measured = relative_variance_of(render_runs(*scene, o, 24, 500), o.spp) / at_one;
    EXPECT_NEAR(predicted[k] / measured, 1.0, 0.1)
        << "rate " << kLightSubpathRates[k] << ": predicted " << predicted[k] << " measured " << measured;
  }
}

// The pilot runs where the render has 16 times its samples or more over
// the pixels it renders (8 a pixel of an image of about 64 x 64, twice
// that where it also chooses among several lights), or under a time
// budget.
TEST(LightSubpaths, PilotRunsOnlyWhereTheRenderIsSixteenTimesItsSize) {
  const auto one_light = guided_room();
  ASSERT_EQ(one_light->lights.all.size(), 1u);
  RenderOptions o = bdpt_options(kLightSubpathsAuto);
  o.width = o.height = 64;
  auto worth = [&](const Scene& scene, uint32_t spp) {
    return worth_a_rate_pilot(scene, bdpt_settings(scene, o, image_region(scene, o), spp));
  };
  EXPECT_TRUE(worth(*one_light, 128));
  EXPECT_FALSE(worth(*one_light, 127));
  EXPECT_TRUE(worth(*one_light, 0)) << "a time budget";
  o.width = o.height = 640;  // (the pilot stays at 64 x 64: 2 samples a pixel are enough)
  EXPECT_TRUE(worth(*one_light, 2));
  EXPECT_FALSE(worth(*one_light, 1));
  const auto two_lights = load_scene(std::string(LANTERN_SOURCE_DIR) + "/scenes/cornell-box.pbrt");
  ASSERT_EQ(two_lights->lights.all.size(), 2u);  // (its light's two triangles)
  o.width = o.height = 32;
  EXPECT_TRUE(worth(*two_lights, 256));
  EXPECT_FALSE(worth(*two_lights, 255));
  // Not choosing the light (--light-choice power or uniform): one pass.
  EXPECT_TRUE(worth_a_rate_pilot(*two_lights, bdpt_settings(*two_lights, o, image_region(*two_lights, o), 128), false));
  // A crop window's pixels are what the render renders; its pilot is the
  // whole image's, at 64 x 64.
  o.width = o.height = 640;
  o.crop_window = {0.f, 0.05f, 0.f, 0.05f};  // 32 x 32 of them
  EXPECT_FALSE(worth(*two_lights, 1023));
  EXPECT_TRUE(worth(*two_lights, 1024));
}

// Every thread count makes the same pilot, bit for bit, and so the same
// choice: its sums run in wave order.
TEST(LightSubpaths, PilotIsTheSameWhateverTheThreads) {
  const auto [one, two] = pilots_on_one_and_all_threads(*guided_room(), bdpt_options(kLightSubpathsAuto));
  EXPECT_EQ(one.rate, two.rate);
  for (size_t k = 0; k < kLightSubpathRates.size(); ++k) {
    EXPECT_EQ(one.error[k], two.error[k]) << k;
    EXPECT_EQ(one.cost[k], two.cost[k]) << k;
    EXPECT_GT(one.error[k], 0.0) << k;
  }
  // Fewer light subpaths cost fewer rays.
  for (size_t k = 1; k < kLightSubpathRates.size(); ++k) EXPECT_LT(one.cost[k], one.cost[k - 1]) << k;
}

// The least error at equal cost wins, but only by 5% or more over rate 1;
// nothing measured leaves rate 1; no rate leaves a pixel of a planned
// render fewer than one light subpath.
TEST(LightSubpaths, ChoiceNeedsAClearGain) {
  EXPECT_EQ(best_light_subpath_rate({1.0, 1.3, 1.8, 2.5}, {10.0, 7.5, 6.2, 5.6}), 1.f);  // 0.975 of rate 1's: not enough
  EXPECT_EQ(best_light_subpath_rate({1.0, 1.2, 1.8, 2.5}, {10.0, 7.5, 6.2, 5.6}), 0.5f);  // 0.90
  EXPECT_EQ(best_light_subpath_rate({1.0, 1.3, 1.8, 2.5}, {10.0, 7.7, 6.2, 5.6}), 1.f);   // 1.001
  EXPECT_EQ(best_light_subpath_rate({1.0, 1.1, 1.2, 1.9}, {10.0, 7.5, 6.2, 5.6}), 0.25f);
  EXPECT_EQ(best_light_subpath_rate({1.0, 1.1, 1.2, 1.3}, {10.0, 7.5, 6.2, 5.6}), 0.125f);
  EXPECT_EQ(best_light_subpath_rate({0.0, 0.0, 0.0, 0.0}, {10.0, 7.5, 6.2, 5.6}), 1.f);
  EXPECT_EQ(best_light_subpath_rate({std::nan(""), 1.0, 1.0, 1.0}, {10.0, 7.5, 6.2, 5.6}), 1.f);
  // Not below one light subpath per pixel of a render of 4 or 1 samples.
  EXPECT_EQ(best_light_subpath_rate({1.0, 1.1, 1.2, 1.3}, {10.0, 7.5, 6.2, 5.6}, 4), 0.25f);
  EXPECT_EQ(best_light_subpath_rate({1.0, 1.1, 1.2, 1.3}, {10.0, 7.5, 6.2, 5.6}, 1), 1.f);
}

// The render reports the rate it used: the pilot's choice under auto
// (with its estimates), the given rate otherwise, and nothing for vcm.
// A render too small for the pilot renders at rate 1, with no estimates.
TEST(LightSubpaths, RenderReportsItsRate) {
  const auto scene = guided_room();
  RenderOptions o = bdpt_options(kLightSubpathsAuto);
  o.time_limit_seconds = 0.01;  // (a time budget: the pilot runs whatever the render's size)
  RenderResult r = render(*scene, o);
  EXPECT_TRUE(r.stats.light_subpath_rate == 1.f || r.stats.light_subpath_rate == 0.5f ||
              r.stats.light_subpath_rate == 0.25f || r.stats.light_subpath_rate == 0.125f);
  EXPECT_EQ(r.stats.light_subpath_candidates.size(), kLightSubpathRates.size());
  EXPECT_EQ(r.stats.light_subpath_error.size(), kLightSubpathRates.size());
  o.time_limit_seconds = 0.0;
  o.spp = 1;
  r = render(*scene, o);
  EXPECT_EQ(r.stats.light_subpath_rate, 1.f);
  EXPECT_TRUE(r.stats.light_subpath_candidates.empty());
  o.light_subpath_rate = 0.3f;
  r = render(*scene, o);
  EXPECT_EQ(r.stats.light_subpath_rate, 0.3f);
  EXPECT_TRUE(r.stats.light_subpath_error.empty());
  o.integrator = Integrator::Vcm;
  o.light_subpath_rate = kLightSubpathsAuto;
  r = render(*scene, o);
  EXPECT_EQ(r.stats.light_subpath_rate, -1.f);
}

TEST(LightSubpaths, RefusesARateOutsideItsRange) {
  const auto scene = guided_room();
  RenderOptions o = bdpt_options(1.f);
  o.spp = 1;
  for (const float bad : {-0.5f, 0.009f, 1e-30f, 1.01f, std::numeric_limits<float>::quiet_NaN(),
                          std::numeric_limits<float>::infinity()}) {
    o.light_subpath_rate = bad;
    EXPECT_THROW(render(*scene, o), std::invalid_argument) << bad;
  }
  for (const char* bad : {"", "0.005", "1.5", "nan", "0.5x", "Auto", "-1"})
    EXPECT_THROW(parse_light_subpaths(bad), std::invalid_argument) << bad;
  EXPECT_EQ(parse_light_subpaths("auto"), kLightSubpathsAuto);
  EXPECT_EQ(parse_light_subpaths("0"), 0.f);  // (the eye subpaths alone: eye_subpaths_alone_test.cpp)
  EXPECT_EQ(parse_light_subpaths("0.25"), 0.25f);
}
