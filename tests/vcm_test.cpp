// Vertex connection and merging (docs/vcm.md): vcm against bdpt where
// bdpt does well, bit-identical images across thread counts, and bad
// settings. The weights themselves are checked against explicit path
// densities in bdpt_mis_test.cpp.
#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iterator>
#include <string>

#include "lantern/render.h"
#include "lantern/scene.h"
#include "expect_error.h"
#include "sanitizer.h"
#include "stat_compare.h"

namespace lantern {
namespace {

// Merging is biased by its radius (it blurs the light over a disk), which
// shrinks as samples grow; at the default radius on the Cornell box the
// blur is far below the noise: vcm's region means match bdpt's within
// 4.5 standard errors plus 1%.
TEST(Vcm, AgreesWithBdptOnTheCornellBoxes) {
  if (LANTERN_ASAN) GTEST_SKIP() << "the Release suite runs it";
  for (const char* name : {"cornell-box", "cornell-box-tiny-light"}) {
    const auto scene = load_scene(std::string(LANTERN_SOURCE_DIR) + "/scenes/" + name + ".pbrt");
    const std::vector<Region> regions = {{0, 0, 32, 32}, {8, 20, 16, 10}, {2, 8, 8, 16}, {22, 8, 8, 16}};
    const RegionStats bdpt = render_stats(*scene, "bdpt", 32, 32, 16, 8, regions);
    expect_means_agree(bdpt, render_stats(*scene, "vcm", 32, 32, 16, 8, regions), 0.01, name);
  }
}

// Options for a merging integrator with render_stats' depth (6).
RenderOptions merging_options(const char* integrator, int width, int height, int spp, float radius) {
  RenderOptions o;
  o.integrator = parse_integrator(integrator);
  o.width = width;
  o.height = height;
  o.spp = spp;
  o.maxdepth = 6;
  o.vcm_radius = radius;
  return o;
}

double mse(const Image& a, const Image& b) {
  double sum = 0.0;
  for (size_t k = 0; k < a.rgb.size(); ++k) sum += double(a.rgb[k] - b.rgb[k]) * double(a.rgb[k] - b.rgb[k]);
  return sum / double(a.rgb.size());
}

// Consistency: as passes add up (and the radius shrinks), vcm's error
// against a long bdpt render of the Cornell box falls. From 8 to 32
// samples per pixel, variance alone would fall 4x, 3.7x with the
// reference's own noise (512 samples); a radius bias that did not shrink,
// or merges that did not average out, would stall it. The test asks 2.5x.
TEST(Vcm, ErrorAgainstBdptFallsWithPasses) {
  if (LANTERN_ASAN) GTEST_SKIP() << "the Release suite runs it";
  const auto scene = load_scene(std::string(LANTERN_SOURCE_DIR) + "/scenes/cornell-box.pbrt");
  RenderOptions o;
  o.width = o.height = 32;
  o.integrator = Integrator::Bdpt;
  o.spp = 512;
  o.seed = 99;
  const Image reference = render(*scene, o).image;
  o.integrator = Integrator::Vcm;
  o.seed = 1;
  o.spp = 8;
  const double coarse = mse(render(*scene, o).image, reference);
  o.spp = 32;
  const double fine = mse(render(*scene, o).image, reference);
  EXPECT_GT(coarse / fine, 2.5) << "mse " << coarse << " at 8 spp, " << fine << " at 32";
}

// With a radius so small that eta = pi r^2 n underflows, Mis(eta) is 0:
// every connection is weighted exactly as bdpt weighs it, and no merge
// happens (or weighs anything). The image is bdpt's, bit for bit.
TEST(Vcm, VanishingRadiusIsBdptBitForBit) {
  const auto scene = load_scene(std::string(LANTERN_SOURCE_DIR) + "/scenes/caustics.pbrt");
  RenderOptions o;
  o.width = 40;
  o.height = 30;
  o.spp = 4;
  o.integrator = Integrator::Bdpt;
  const Image bdpt = render(*scene, o).image;
  o.integrator = Integrator::Vcm;
  o.vcm_radius = 1e-20f;
  const RenderResult vcm = render(*scene, o);
  EXPECT_EQ(vcm.stats.merges, 0u);
  ASSERT_EQ(bdpt.rgb.size(), vcm.image.rgb.size());
  EXPECT_EQ(std::memcmp(bdpt.rgb.data(), vcm.image.rgb.data(), bdpt.rgb.size() * sizeof(float)), 0)
      << "vcm without merging differs from bdpt";
}

// Progressive photon mapping on the same light vertices: only merges
// (unweighted) and lights seen directly. On the Cornell box's diffuse
// walls, with a disk of 2% of the box, its means match bdpt's within 4.5
// standard errors plus 3% (the blur of the disk at corners and edges).
TEST(Vcm, PhotonMappingAgreesWithBdptOnTheCornellBox) {
  if (LANTERN_ASAN) GTEST_SKIP() << "the Release suite runs it";
  const auto scene = load_scene(std::string(LANTERN_SOURCE_DIR) + "/scenes/cornell-box.pbrt");
  const std::vector<Region> regions = {{0, 0, 32, 32}, {8, 20, 16, 10}};
  const RegionStats bdpt = render_stats(*scene, "bdpt", 32, 32, 16, 8, regions);
  expect_means_agree(bdpt, stats_of(render_runs(*scene, merging_options("ppm", 32, 32, 16, 10.f), 8, 1000), regions),
                     0.03, "ppm");
}

// Bidirectional photon mapping: merges at every non-specular eye vertex,
// weighted against each other, and no connections. With a disk of 2% of
// the box its means match bdpt's within 4.5 standard errors plus 3%.
TEST(Vcm, BidirectionalPhotonMappingAgreesWithBdptOnTheCornellBox) {
  if (LANTERN_ASAN) GTEST_SKIP() << "the Release suite runs it";
  const auto scene = load_scene(std::string(LANTERN_SOURCE_DIR) + "/scenes/cornell-box.pbrt");
  const std::vector<Region> regions = {{0, 0, 32, 32}, {8, 20, 16, 10}, {2, 8, 8, 16}};
  const RegionStats bdpt = render_stats(*scene, "bdpt", 32, 32, 16, 8, regions);
  expect_means_agree(bdpt, stats_of(render_runs(*scene, merging_options("bpm", 32, 32, 16, 10.f), 8, 1000), regions),
                     0.03, "bpm");
}

// Without connections and with one bounce, the only strategies left are a
// merge at the first eye vertex (whose weight, 1 / (1 + 0 + 0), is exactly
// 1) and lights seen directly: bpm's image is ppm's, bit for bit.
TEST(Vcm, OneBounceBpmIsPpmBitForBit) {
  const auto scene = load_scene(std::string(LANTERN_SOURCE_DIR) + "/scenes/cornell-box.pbrt");
  RenderOptions o = merging_options("ppm", 24, 24, 4, 10.f);
  o.maxdepth = 1;
  const RenderResult ppm = render(*scene, o);
  o.integrator = Integrator::Bpm;
  const RenderResult bpm = render(*scene, o);
  EXPECT_GT(bpm.stats.merges, 0u);
  EXPECT_EQ(bpm.stats.merges, ppm.stats.merges);
  ASSERT_EQ(bpm.image.rgb.size(), ppm.image.rgb.size());
  EXPECT_EQ(std::memcmp(bpm.image.rgb.data(), ppm.image.rgb.data(), bpm.image.rgb.size() * sizeof(float)), 0)
      << "one-bounce bpm differs from ppm";
}

// Per-strategy images (--strategies): with merges among them, the weighted
// images of all strategies add up to the image, pixel by pixel, also
// through a film sensor that scales and white-balances (color/sensor.h).
TEST(Vcm, StrategyImagesAddUpToTheImage) {
  std::ifstream file(std::string(LANTERN_SOURCE_DIR) + "/scenes/cornell-box.pbrt");
  std::string text((std::istreambuf_iterator<char>(file)), std::istreambuf_iterator<char>());
  const size_t film = text.find("Film \"rgb\"");
  ASSERT_NE(film, std::string::npos);
  text.insert(film + 10, " \"float iso\" 200 \"float whitebalance\" 3000");
  const auto scene = load_scene_from_string(text, "cornell-box-sensor.pbrt");
  for (const char* integrator : {"bdpt", "vcm", "bpm"}) {
    RenderOptions o = merging_options(integrator, 24, 24, 4, 20.f);
    o.strategies = true;
    const RenderResult r = render(*scene, o);
    std::vector<double> sum(r.image.rgb.size(), 0.0);
    bool merges = false;
    for (const StrategyImage& im : r.strategies) {
      merges |= im.merge;
      for (size_t k = 0; k < sum.size(); ++k) sum[k] += im.weighted.rgb[k];
    }
    EXPECT_EQ(merges, std::string(integrator) != "bdpt") << integrator;
    for (size_t k = 0; k < sum.size(); ++k)
      ASSERT_NEAR(sum[k], r.image.rgb[k], 1e-4 + 1e-4 * r.image.rgb[k]) << integrator << " at " << k / 3;
  }
}

TEST(Vcm, ThreadCountsGiveTheSameBits) {
  const auto scene = load_scene(std::string(LANTERN_SOURCE_DIR) + "/scenes/pool.pbrt");
  RenderOptions o = merging_options("vcm", 32, 24, 2, 0.1f);  // merges happen even at this size
  expect_thread_invariant(*scene, o, {"vcm", "bpm", "ppm"});
  const auto fog = load_scene(std::string(LANTERN_SOURCE_DIR) + "/scenes/volumetric-caustic.pbrt");
  o.vcm_radius = 0.f;
  expect_thread_invariant(*fog, o, {"vcm", "bpm"});
}

// Merges do happen on the pool's floor (an SDS path), and the stats say
// so, with the radius of the last pass: 40 samples run as passes of one
// sample per pixel, the last starting at sample 39, so
// r = 0.1 * 40^((0.75 - 1) / 2).
TEST(Vcm, MergesOnThePoolFloor) {
  const auto scene = load_scene(std::string(LANTERN_SOURCE_DIR) + "/scenes/pool.pbrt");
  const RenderResult r = render(*scene, merging_options("vcm", 32, 24, 40, 0.1f));
  EXPECT_GT(r.stats.merges, 0u);
  EXPECT_FLOAT_EQ(r.stats.vcm_radius, 0.1f);
  EXPECT_NEAR(r.stats.vcm_last_radius, 0.1 * std::pow(40.0, -0.125), 1e-6);
  EXPECT_EQ(r.stats.nonfinite_samples, 0u);
}

// With merging, a render of N samples per pixel runs N passes of one, as
// a timed render does, so a pixel's samples merge with the light vertices
// of N different waves (in passes of 16 they merged with one wave's: on
// the pool at 240x180 and 64 spp, relMSE 0.027 then, 0.0048 now, where a
// timed render reaching 46 spp has 0.0066; docs/vcm.md), and the radius
// shrinks sample by sample.
TEST(Vcm, MergingRendersPassesOfOneSample) {
  const auto scene = load_scene(std::string(LANTERN_SOURCE_DIR) + "/scenes/pool.pbrt");
  for (const char* integrator : {"vcm", "bpm", "ppm"}) {
    std::vector<uint32_t> spps;
    RenderHooks hooks;
    hooks.pass_done = [&](uint32_t spp) { spps.push_back(spp); };
    render(*scene, merging_options(integrator, 16, 12, 3, 0.1f), hooks);
    EXPECT_EQ(spps, (std::vector<uint32_t>{1, 2, 3})) << integrator;
  }
  std::vector<uint32_t> spps;
  RenderHooks hooks;
  hooks.pass_done = [&](uint32_t spp) { spps.push_back(spp); };
  render(*scene, merging_options("bdpt", 16, 12, 3, 0.1f), hooks);
  EXPECT_EQ(spps, (std::vector<uint32_t>{3})) << "bdpt keeps its passes of up to 16";
}

// Issue 30's budget bug, by its error: on the pool, vcm's image after
// `--spp 16` and after a time budget stopped at 16 passes leave the same
// relative error against a long render, within 20% (when a pass was 16
// samples of each pixel, all merging with one wave's light vertices, the
// sample budget was 6.7 times worse), and the pixels on the borders of the
// 16x16 tiles a wave is made of are no noisier than those inside them
// (that budget's images showed seams along the tiles).
TEST(Vcm, SampleAndTimeBudgetsLeaveTheSameError) {
  if (LANTERN_ASAN) GTEST_SKIP() << "the Release suite runs it";
  const auto scene = load_scene(std::string(LANTERN_SOURCE_DIR) + "/scenes/pool.pbrt");
  const int w = 96, h = 64;
  // (The reference's own error adds to both renders' alike: about 16 / 256
  // of theirs, somewhat more as vcm's radius shrinks more slowly than 1/N.)
  const Image ref = render(*scene, merging_options("vcm", w, h, 256, 0.f)).image;
  // Per pixel: relative squared error, Rousselle et al.'s, over channels;
  // the light's own pixels (far brighter than the rest) left out.
  double ref_mean = 0.0;
  for (float v : ref.rgb) ref_mean += double(v) / double(ref.rgb.size());
  struct Error { double all = 0, border = 0, inside = 0; size_t n_border = 0, n_inside = 0; };
  auto error = [&](const Image& a) {
    Error e;
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) {
        const size_t p = size_t(y * w + x) * 3;
        double r = 0.0, sq = 0.0;
        for (int c = 0; c < 3; ++c) {
          const double d = double(a.rgb[p + size_t(c)]) - ref.rgb[p + size_t(c)];
          sq += d * d / (double(ref.rgb[p + size_t(c)]) * ref.rgb[p + size_t(c)] + 1e-2);
          r += ref.rgb[p + size_t(c)] / 3.0;
        }
        if (r > 20.0 * ref_mean) continue;
        const bool border = x % 16 == 0 || x % 16 == 15 || y % 16 == 0 || y % 16 == 15;
        (border ? e.border : e.inside) += sq;
        ++(border ? e.n_border : e.n_inside);
      }
    e.all = (e.border + e.inside) / double(e.n_border + e.n_inside);
    e.border /= double(e.n_border);
    e.inside /= double(e.n_inside);
    return e;
  };
  const RenderResult by_spp = render(*scene, merging_options("vcm", w, h, 16, 0.f));
  RenderOptions timed = merging_options("vcm", w, h, 16, 0.f);
  timed.time_limit_seconds = 3600.0;
  std::atomic<bool> stop{false};
  RenderHooks hooks;
  hooks.cancel = &stop;
  hooks.pass_done = [&](uint32_t spp) {
    if (spp >= 16) stop = true;
  };
  const RenderResult by_time = render(*scene, timed, hooks);
  const double spp_time = double(by_time.stats.samples) / double(w * h);
  ASSERT_GE(spp_time, 16.0);
  const Error a = error(by_spp.image), b = error(by_time.image);
  std::printf("pool, vcm: --spp 16 relMSE %.5f (tile borders %.5f, inside %.5f); timed, %.2f spp: %.5f (%.5f, %.5f)\n",
              a.all, a.border, a.inside, spp_time, b.all, b.border, b.inside);
  // (error times samples: a timed render may end a pass or so later)
  const double ratio = a.all * 16.0 / (b.all * spp_time);
  EXPECT_GT(ratio, 1.0 / 1.2) << a.all << " against " << b.all << " at " << spp_time << " spp";
  EXPECT_LT(ratio, 1.2) << a.all << " against " << b.all << " at " << spp_time << " spp";
  for (const Error& e : {a, b}) {
    EXPECT_LT(e.border / e.inside, 1.25) << "tile borders " << e.border << ", inside " << e.inside;
    EXPECT_GT(e.border / e.inside, 0.8) << "tile borders " << e.border << ", inside " << e.inside;
  }
}

// pbrt-v4's stochastic progressive photon mapper converges to vcm's image:
// an "sppm" Integrator renders with vcm, its "radius" the first merging
// radius.
TEST(Vcm, SppmScenesRenderWithVcm) {
  const std::string world = "WorldBegin\nLightSource \"point\" \"rgb I\" [1 1 1]\n";
  const auto scene = load_scene_from_string("Integrator \"sppm\" \"float radius\" 0.25\n" + world, "sppm.pbrt", {});
  EXPECT_EQ(scene->settings.integrator, Integrator::Vcm);
  EXPECT_FLOAT_EQ(scene->settings.merge_radius, 0.25f);
  EXPECT_FLOAT_EQ(load_scene_from_string("Integrator \"sppm\"\n" + world, "sppm.pbrt", {})->settings.merge_radius, 0.f);
  expect_load_error("Integrator \"sppm\"\n  \"float radius\" -1\n" + world, "bad.pbrt",
                    {"bad.pbrt:2", "radius", "positive"});
  // Its "photonsperiteration": -1 (a pass's pixels) unless given; the
  // default wave holds that many light subpaths, up to kPhotonWaveLimit.
  EXPECT_EQ(scene->settings.photons_per_iteration, -1);
  const auto given =
      load_scene_from_string("Integrator \"sppm\" \"integer photonsperiteration\" 5000\n" + world, "sppm.pbrt", {});
  EXPECT_EQ(given->settings.photons_per_iteration, 5000);
  EXPECT_EQ(load_scene_from_string("Integrator \"bdpt\"\n" + world, "bdpt.pbrt", {})->settings.photons_per_iteration,
            0);
  for (const char* bad : {"0", "-2"})
    expect_load_error("Integrator \"sppm\"\n  \"integer photonsperiteration\" " + std::string(bad) + "\n" + world,
                      "bad.pbrt", {"bad.pbrt:2", "photonsperiteration", "positive"});
  EXPECT_EQ(default_wave_size(Integrator::Vcm, 5000), 5000);
  EXPECT_EQ(default_wave_size(Integrator::Vcm, -1), kPhotonWaveLimit);
  EXPECT_EQ(default_wave_size(Integrator::Ppm, int64_t(1) << 40), kPhotonWaveLimit);
  EXPECT_EQ(default_wave_size(Integrator::Vcm, 0), kMergingWaveSize);
  EXPECT_EQ(default_wave_size(Integrator::Bdpt, -1), kPathWaveSize);
}

// An sppm scene's vcm merges with a whole pass's light subpaths (pbrt-v4's
// photons per iteration): on the pool at 160x120, 19,200 per wave where
// the default wave holds 9,600. Each merge divides by the light subpaths
// it had, while the weights count at most kMergeWeightPaths (16,384), so
// the floor's region means agree with the default wave's (4.5 standard
// errors plus 2%, the weights' small difference in blur), and the
// pixels' variance over 8 renders falls (measured: 0.54 of the default's;
// photon noise is most of it there). Dividing by the weights' count
// instead makes the floor 17% bright; waves of the default size leave the
// variance as it was: either fails.
TEST(Vcm, WavesOfAWholePassMergeWithMoreLightSubpaths) {
  if (LANTERN_ASAN) GTEST_SKIP() << "the Release suite runs it";
  const auto scene = load_scene(std::string(LANTERN_SOURCE_DIR) + "/scenes/pool.pbrt");
  const int w = 160, h = 120, runs = 8;
  RenderOptions o = merging_options("vcm", w, h, 4, 0.f);
  o.wave_size = kMergingWaveSize;
  EXPECT_EQ(render(*scene, o).stats.vcm_wave_paths, 9600u);
  const std::vector<Image> small = render_runs(*scene, o, runs, 100);
  o.wave_size = default_wave_size(o.integrator, scene->settings.photons_per_iteration);
  EXPECT_EQ(render(*scene, o).stats.vcm_wave_paths, uint32_t(w * h));
  const std::vector<Image> whole = render_runs(*scene, o, runs, 100);
  const std::vector<Region> floor = {{8, 72, 60, 40}, {100, 84, 52, 30}, {30, 40, 50, 20}};
  expect_means_agree(stats_of(small, floor), stats_of(whole, floor), 0.02, "pool floor");
  auto variance = [&](const std::vector<Image>& images) {  // summed over the floor's pixels and channels
    double sum = 0.0;
    for (const Region& g : floor)
      for (int y = g.y0; y < g.y0 + g.h; ++y)
        for (int x = g.x0; x < g.x0 + g.w; ++x)
          for (int c = 0; c < 3; ++c) {
            double m = 0.0, m2 = 0.0;
            for (const Image& im : images) {
              m += im.at(x, y)[c] / double(runs);
              m2 += double(im.at(x, y)[c]) * im.at(x, y)[c] / double(runs);
            }
            sum += m2 - m * m;
          }
    return sum;
  };
  const double ratio = variance(whole) / variance(small);
  std::printf("pool floor, variance with a whole pass's light subpaths over the default wave's: %.3f\n", ratio);
  EXPECT_LT(ratio, 0.8);
}

// In scenes with media, merging happens on surfaces; medium vertices only
// connect (their MIS is checked in bdpt_mis_test.cpp). vcm's region means
// match bdpt's in a fog sphere, in fog around a glass ball's caustic
// (merges on the floor through the fog), and with glowing media (volume
// lights), within 4.5 standard errors plus 1%.
TEST(Vcm, AgreesWithBdptInMedia) {
  if (LANTERN_ASAN) GTEST_SKIP() << "the Release suite runs it";
  const std::vector<Region> regions = {{0, 0, 32, 24}, {8, 6, 16, 12}, {0, 16, 32, 8}};
  for (const char* name : {"perf/media/fog-sphere", "scenes/volumetric-caustic", "perf/media/glowing-fog"}) {
    const auto scene = load_scene(std::string(LANTERN_SOURCE_DIR) + "/" + name + ".pbrt");
    const RegionStats bdpt = render_stats(*scene, "bdpt", 32, 24, 16, 8, regions);
    expect_means_agree(bdpt, render_stats(*scene, "vcm", 32, 24, 16, 8, regions), 0.01, name);
  }
}

// bpm in media: merges on surfaces and in balls in the fog, and emission
// found along eye subpaths that have passed no vertex where they could
// merge (lights seen through the fog's boundary). With a radius of 1.2% of
// the scene's (a ball near the fog sphere's boundary misses the light
// vertices outside it: at 5% the sphere came out 8% dark), within 4.5
// standard errors plus 3% of bdpt.
TEST(Vcm, BidirectionalPhotonMappingAgreesWithBdptInMedia) {
  if (LANTERN_ASAN) GTEST_SKIP() << "the Release suite runs it";
  const std::vector<Region> regions = {{0, 0, 32, 24}, {8, 6, 16, 12}};
  for (const char* name : {"perf/media/fog-sphere", "perf/media/glowing-fog"}) {
    const auto scene = load_scene(std::string(LANTERN_SOURCE_DIR) + "/" + name + ".pbrt");
    const RegionStats bdpt = render_stats(*scene, "bdpt", 32, 24, 16, 8, regions);
    const RenderOptions o = merging_options("bpm", 32, 24, 16, 0.012f * scene->lights.scene_radius);
    expect_means_agree(bdpt, stats_of(render_runs(*scene, o, 8, 1000), regions), 0.03, name);
  }
}

// The same at maxdepth 1, where a merge at the first eye vertex needs a
// light vertex at the last depth: light vertices in a medium must be kept
// there as those on surfaces are (without them single scattering in the
// fog went missing: bpm came out 6.5% dark on scenes/smoke.pbrt).
TEST(Vcm, BidirectionalPhotonMappingKeepsTheLastMediumVertices) {
  if (LANTERN_ASAN) GTEST_SKIP() << "the Release suite runs it";
  const std::vector<Region> regions = {{0, 0, 32, 24}, {8, 6, 16, 12}};
  const auto scene = load_scene(std::string(LANTERN_SOURCE_DIR) + "/perf/media/fog-sphere.pbrt");
  RenderOptions o = merging_options("bpm", 32, 24, 16, 0.012f * scene->lights.scene_radius);
  o.maxdepth = 1;
  const RegionStats bpm = stats_of(render_runs(*scene, o, 8, 1000), regions);
  o.integrator = Integrator::Bdpt;
  expect_means_agree(stats_of(render_runs(*scene, o, 8, 1000), regions), bpm, 0.03, "maxdepth 1");
}

TEST(Vcm, BadSettingsAreClearErrors) {
  const auto scene = load_scene(std::string(LANTERN_SOURCE_DIR) + "/scenes/cornell-box.pbrt");
  RenderOptions o = merging_options("vcm", 8, 8, 1, 0.f);
  o.vcm_alpha = 0.f;
  EXPECT_THROW(render(*scene, o), std::invalid_argument);
  o.vcm_alpha = 0.75f;
  o.vcm_radius = -1.f;
  EXPECT_THROW(render(*scene, o), std::invalid_argument);
}

}  // namespace
}  // namespace lantern
