// A guided render goes on as an unguided one once its field has learnt
// (integrator/pass_layout.h): passes of one sample per pixel while the
// field learns, then the passes an unguided render of its budget takes,
// and split camera samples, whether the guide stopped or goes on.
#include <gtest/gtest.h>

#include <cstdio>
#include <mutex>
#include <string>
#include <vector>

#include "film/checkpoint.h"
#include "guided_rooms.h"
#include "guiding/sd_tree.h"
#include "integrator/adaptive_sampling.h"
#include "integrator/pass_layout.h"
#include "integrator/render_checkpoints.h"
#include "lantern/render.h"
#include "lantern/scene.h"
#include "sanitizer.h"
#include "stat_compare.h"
#include "stop_and_resume.h"

using namespace lantern;
using namespace lantern::guiding_test;

namespace {

std::shared_ptr<Scene> cornell_box() {
  return load_scene(std::string(LANTERN_SOURCE_DIR) + "/scenes/cornell-box.pbrt");
}

// The Cornell box's quadtree guide stops after its third iteration (pass
// 7, guide_stop_test.cpp); passes of 16 samples whose camera samples split
// in 4 take over from sample 16 (passes 7 to 15 are of one sample, unguided).
RenderOptions stopping_options(uint32_t spp) {
  RenderOptions o = guided_options(true);
  o.guide_stop = true;
  o.split = 4;
  o.width = 64, o.height = 48;
  o.spp = int(spp);
  o.seed = 1;
  o.collect_stats = true;
  return o;
}

}  // namespace

// The units of a render laid out in passes of one sample up to sample 16
// and of 16 from there are numbered 0, 1, 2, ... each once, pass after
// pass, whatever the wave counts of the two layouts.
TEST(PassLayout, TheSecondLayoutsUnitsFollowTheFirsts) {
  const uint32_t pixels = 1000, total = 45;
  const PassLayout a = pass_layout(1, pixels, false, 128);
  EXPECT_EQ(a.waves, 8u);
  const PassLayout b = pass_layout(16, pixels, false, 128, &a, 16);
  EXPECT_EQ(b.pixels_per_wave, 8u);
  EXPECT_EQ(b.waves, 125u);
  EXPECT_EQ(b.first_pass, 16u);
  uint64_t expected = 0;
  for (uint32_t first = 0; first < total;) {
    const PassLayout& l = first < 16 ? a : b;
    EXPECT_EQ(l.pass_of(first), first < 16 ? first : 16 + (first - 16) / 16);
    for (uint32_t w = 0; w < l.waves; ++w) EXPECT_EQ(l.unit_of(first, w), expected++) << first << " " << w;
    first += l.pass_spp;
  }
  EXPECT_EQ(b.units_to(total), expected);  // (the last pass, cut short at 45, counts whole)
  EXPECT_EQ(a.units_to(16), b.first_unit);
  // A checkpoint's bound holds every relayout the field may make: after
  // pass 0, 1, 3, 7, 15 or 31 (from 0, 16, 16, 16, 16, 32: 375, 378 or
  // 128 x 2 + 125 = 381 units), or none (360).
  EXPECT_EQ(most_guided_units(a, 16, pixels, false, 128, total), 381u);
}

// Under adaptive sampling the second layout begins after the pair of
// samples whose pixels were decided before the field was known to have
// learnt (pass_layout.h), and the adaptive passes are numbered on across
// it: pairs of one-sample passes, then passes of 16.
TEST(PassLayout, AdaptiveRelayoutBeginsAfterTheDecidedPairs) {
  EXPECT_EQ(relayout_from(7, 16, false), 16u);
  EXPECT_EQ(relayout_from(7, 16, true), 16u);
  EXPECT_EQ(relayout_from(15, 16, false), 16u);
  EXPECT_EQ(relayout_from(15, 16, true), 32u);  // (the pair 16, 17 was decided at sample 14)
  EXPECT_EQ(relayout_from(31, 16, true), 48u);
  EXPECT_EQ(relayout_from(7, 5, true), 10u);  // (a pair ends there)
  Film film(8, 8, PixelFilter{});
  std::mutex mutex;
  const std::vector<uint32_t> order = tile_order(8, 8);
  AdaptiveGoal goal;
  goal.budget = 64.0 * 40;
  AdaptivePasses adaptive(film, mutex, order, 64, 2, goal);
  EXPECT_EQ(adaptive.pass_of(31), 15u);
  adaptive.relayout(32, 16);
  EXPECT_EQ(adaptive.pass_of(30), 15u);
  EXPECT_EQ(adaptive.pass_of(31), 15u);
  EXPECT_EQ(adaptive.pass_of(32), 16u);
  EXPECT_EQ(adaptive.pass_of(47), 16u);
  EXPECT_EQ(adaptive.pass_of(48), 17u);
}

// Guided checkpoints of the layout before (one sample per pass to the
// end, "guiding=1") number their units otherwise: refused by name.
TEST(PassLayout, GuidedFingerprintNamesTheLayout) {
  RenderOptions o = guided_options(true);
  ImageRegion region;
  region.width = region.height = 8;
  o.split = 1;  // (whole camera samples, as under "2")
  EXPECT_NE(sequence_fingerprint(o, region).find("\nguiding=2\n"), std::string::npos);
  o.split = 4;  // (whole camera samples while the guide went on under "2")
  EXPECT_NE(sequence_fingerprint(o, region).find("\nguiding=3\n"), std::string::npos);
  o.split = 1;
  o.adaptive = true;  // (one sample per pass to the end under "2")
  EXPECT_NE(sequence_fingerprint(o, region).find("\nguiding=3\n"), std::string::npos);
  o.integrator = Integrator::Vcm;  // (merging: passes of one sample to the end, as under "2")
  EXPECT_NE(sequence_fingerprint(o, region).find("\nguiding=2\n"), std::string::npos);
}

// Once the field has learnt, the render's camera samples split as the
// unguided render's do (--split 4), whether its guide stopped (after pass
// 7: split from sample 16) or goes on (learnt to pass 31: from sample 32,
// each path of a camera sample drawing from the guide at the shared first
// hit with its own numbers); it takes its budget's samples, no more, no
// fewer, and its image is the unguided one's: region means over
// independent renders agree within 4.5 standard errors.
TEST(GuidedRelayout, LearntFieldSplitsAndConvergesToTheUnguidedImage) {
  if (LANTERN_ASAN) GTEST_SKIP() << "whole renders' verdicts: the Release suite runs it";
  const auto box = cornell_box();
  std::vector<Region> regions;
  for (int y = 0; y < 48; y += 16)
    for (int x = 0; x < 64; x += 16) regions.push_back({x, y, 16, 16});
  RenderOptions plain = stopping_options(64);
  plain.guiding = false;
  const RegionStats unguided = stats_of(render_runs(*box, plain, 6, 100), regions);
  for (const bool stops : {true, false}) {
    RenderOptions o = stopping_options(64);
    o.guide_stop = stops;
    const RenderResult r = render(*box, o);
    EXPECT_EQ(r.stats.guiding_stopped_after, stops ? int32_t(SDTree::kFirstJudged) : -1);
    EXPECT_EQ(r.stats.split, 4u) << stops;
    EXPECT_EQ(r.stats.samples, uint64_t(64) * 48 * 64) << stops;
    const RegionStats guided = stats_of(render_runs(*box, o, 6, 200), regions);
    max_z(unguided, guided);
    expect_means_agree(unguided, guided, 0.0, stops ? "guided path, stopped and split" : "guided path, split");
  }
}

// A render stopped before the relayout, inside the passes of one sample
// that lead up to it and after it, on one and two threads in turn,
// resumes to the straight render's image bit for bit: the second layout
// and its split follow from the field its checkpoint keeps.
TEST(GuidedRelayout, ResumesAcrossTheRelayoutToTheStraightImage) {
  const auto box = cornell_box();
  RenderOptions o = stopping_options(24);
  o.wave_size = 1024;  // 3 waves a pass of one sample, 48 of sixteen
  o.collect_stats = false;
  expect_resumes_to_the_straight_image(*box, o, "lantern_guided_relayout.ckpt", 5, 7, 3, "path, split after the stop");
}

// A finished guided render's film file holds every unit it counts, whether
// a second layout came (24 spp: from sample 16) or none could (12 spp: the
// stop after pass 7 leaves no pass of 12 samples, so no camera sample
// splits and no split is chosen): --part 1/1's film files merge as
// finished (merge_parts.cpp).
TEST(GuidedRelayout, AFinishedRendersFilmCountsItsOwnUnits) {
  if (LANTERN_ASAN) GTEST_SKIP() << "whole renders' verdicts: the Release suite runs it";
  const auto box = cornell_box();
  for (const uint32_t spp : {24u, 12u}) {
    RenderOptions o = stopping_options(spp);
    o.wave_size = 1024;
    o.film_path = ::testing::TempDir() + "/lantern_guided_relayout.film";
    const RenderResult r = render(*box, o);
    EXPECT_EQ(r.stats.guiding_stopped_after, int32_t(SDTree::kFirstJudged)) << spp;
    EXPECT_EQ(r.stats.split, spp == 24 ? 4u : 1u) << spp;
    Film film(0, 0, PixelFilter{});
    const CheckpointInfo ci = read_film_file(o.film_path, film);
    EXPECT_EQ(ci.done.size(), ci.passes * ci.waves) << spp;
    EXPECT_EQ(ci.done.size(), spp == 24 ? 16u * 3 + 48 : 12u * 3) << spp;
    std::remove(o.film_path.c_str());
  }
}

// An adaptive guided render lays its passes out again too. Where the guide
// stopped (after pass 7), its camera samples split as the unguided
// render's do, it spends its budget of samples exactly, and its image is
// the unguided adaptive render's: region means over independent renders
// agree within 4.5 standard errors.
TEST(GuidedRelayout, AdaptiveRendersSplitAfterTheStopAndSpendTheirBudget) {
  if (LANTERN_ASAN) GTEST_SKIP() << "whole renders' verdicts: the Release suite runs it";
  const auto box = cornell_box();
  RenderOptions o = stopping_options(64);
  o.adaptive = true;
  const RenderResult stopped = render(*box, o);
  EXPECT_EQ(stopped.stats.guiding_stopped_after, int32_t(SDTree::kFirstJudged));
  EXPECT_EQ(stopped.stats.split, 4u);
  EXPECT_EQ(stopped.stats.samples, uint64_t(64) * 48 * 64);
  EXPECT_GT(stopped.stats.max_spp, 64u);  // (the budget went where it pays)

  std::vector<Region> regions;
  for (int y = 0; y < 48; y += 16)
    for (int x = 0; x < 64; x += 16) regions.push_back({x, y, 16, 16});
  RenderOptions plain = o;
  plain.guiding = false;
  const RegionStats unguided = stats_of(render_runs(*box, plain, 6, 100), regions);
  const RegionStats guided = stats_of(render_runs(*box, o, 6, 200), regions);
  max_z(unguided, guided);
  expect_means_agree(unguided, guided, 0.0, "adaptive guided path, stopped and split");
}

// An adaptive guided render whose field learns to pass 15 (--spp 40, the
// guide kept): passes of one sample to sample 32, then of 16. Stopped
// inside both and resumed, on one and two threads in turn, it ends on the
// straight render's image and spends its budget exactly.
TEST(GuidedRelayout, AdaptiveRendersResumeAcrossTheRelayout) {
  const auto box = cornell_box();
  RenderOptions o = stopping_options(40);
  o.guide_stop = false;
  o.adaptive = true;
  o.wave_size = 1024;  // 3 waves a pass of one sample, 48 of sixteen
  o.collect_stats = false;
  const RenderResult straight = render(*box, o);
  EXPECT_EQ(straight.stats.samples, uint64_t(40) * 48 * 64);
  expect_resumes_to_the_straight_image(*box, o, "lantern_guided_adaptive.ckpt", 9, 13, 3, "adaptive, guide kept");
}

// A budget whose passes were pairs of one sample before the relayout
// leaves a remainder no block of 16 pixels fits in a pass of 16: the
// render ends there, rather than going on through passes no pixel takes to
// adaptive sampling's limit of samples per pixel (the spotlit room at 240
// x 180, 128 spp, took five times as long so).
TEST(GuidedRelayout, AdaptiveBudgetEndsWhenNoBlockFits) {
  if (LANTERN_ASAN) GTEST_SKIP() << "whole renders' verdicts: the Release suite runs it";
  const auto box = cornell_box();
  for (const uint32_t spp : {40u, 48u, 56u, 64u}) {
    RenderOptions o = stopping_options(spp);
    o.guide_stop = false;
    o.adaptive = true;
    uint32_t reached = 0;
    RenderHooks hooks;
    hooks.pass_done = [&](uint32_t s) { reached = s; };
    const RenderResult r = render(*box, o, hooks);
    EXPECT_LE(r.stats.samples, uint64_t(spp) * 48 * 64) << spp;
    EXPECT_GT(r.stats.samples + 16 * 16, uint64_t(spp) * 48 * 64) << spp;  // (to a block of a pass)
    EXPECT_LE(reached, r.stats.max_spp + 16) << spp;
  }
}
