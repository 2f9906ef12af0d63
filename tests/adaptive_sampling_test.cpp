// Adaptive sampling (--target-error and --adaptive,
// integrator/adaptive_sampling.h): the error it estimates against the
// error measured against a reference, the target it stops at, the budget
// it spends and what that gains over uniform sampling, an image whose means
// are a reference's, and the determinism every render has (threads,
// resume).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <stdexcept>

#include "film/image_metrics.h"
#include "lantern/render.h"
#include "lantern/scene.h"
#include "sanitizer.h"
#include "stat_compare.h"
#include "stop_and_resume.h"

namespace lantern {
namespace {

std::shared_ptr<Scene> shipped(const char* name) { return load_scene(std::string(LANTERN_SOURCE_DIR) + "/scenes/" + name); }

// The independent sampler: its samples are independent, which the
// half-buffer estimate assumes (with the low-discrepancy samplers it
// overestimates: the Cornell box at 64 spp, 1.7x with zsobol).
RenderOptions small(const std::string& integrator, int spp) {
  RenderOptions o;
  o.integrator = parse_integrator(integrator);
  o.sampler.type = SamplerKind::Independent;
  o.spp = spp;
  o.width = 32;
  o.height = 32;
  o.maxdepth = 5;
  o.wave_size = 1024;
  return o;
}

double relmse(const Image& a, const Image& ref) {
  double e = 0.0;
  for (size_t k = 0; k < a.rgb.size(); ++k) {
    const double d = double(a.rgb[k]) - double(ref.rgb[k]);
    e += d * d / (double(ref.rgb[k]) * double(ref.rgb[k]) + kRelMseEpsilon);
  }
  return e / double(a.rgb.size());
}

Image reference(const Scene& scene, const std::string& integrator, int spp = 1024) {
  RenderOptions o = small(integrator, spp);
  o.seed = 99;
  return render(scene, o).image;
}

// With every block sampled alike (a target no block reaches), the estimate
// is the measured relMSE within a factor 1.5, on three scenes: a diffuse
// box (path and bdpt, whose light tracing's splats it includes), glossy
// and textured objects, and fog lit by a spot (media). (Caustics through glass in bdpt: 0.53, see
// docs/adaptive-sampling.md.)
TEST(AdaptiveSampling, EstimateTracksTheMeasuredError) {
  if (LANTERN_ASAN) GTEST_SKIP() << "references at 512 spp";
  const struct {
    const char* scene;
    const char* integrator;
  } cases[] = {{"cornell-box.pbrt", "path"},
               {"appearance.pbrt", "path"},
               {"cornell-box.pbrt", "bdpt"},
               {"smoke.pbrt", "path"},
               {"cornell-box.pbrt", "vcm"}};
  for (const auto& c : cases) {
    auto scene = shipped(c.scene);
    // (At 512 spp the reference's own error adds an eighth to the measured one.)
    const Image ref = reference(*scene, c.integrator, 512);
    RenderOptions o = small(c.integrator, 64);
    o.target_error = 1e-12;
    const RenderResult r = render(*scene, o);
    const double measured = relmse(r.image, ref);
    ASSERT_GT(r.stats.estimated_relmse, 0.0) << c.scene;
    const double ratio = r.stats.estimated_relmse / measured;
    std::printf("%s (%s): estimated relMSE %.5f, measured %.5f\n", c.scene, c.integrator, r.stats.estimated_relmse,
                measured);
    EXPECT_GT(ratio, 1.0 / 1.5) << c.scene << ": estimated " << r.stats.estimated_relmse << ", measured " << measured;
    EXPECT_LT(ratio, 1.5) << c.scene << ": estimated " << r.stats.estimated_relmse << ", measured " << measured;
  }
}

// With zsobol, the default sampler, the halves are runs of consecutive
// indices of each pass (halves_bit): each is as good a pattern as a pass
// of half the samples. The Cornell box in bdpt at 64 spp is estimated at
// 1.25 times its measured error; halved into odd and even indices, each
// half a worse pattern than the whole, at 1.85, and the test fails.
TEST(AdaptiveSampling, EstimateWithZSobolHalvesRunsOfAPass) {
  if (LANTERN_ASAN) GTEST_SKIP() << "a reference at 1024 spp";
  auto scene = shipped("cornell-box.pbrt");
  RenderOptions ro = small("bdpt", 1024);
  ro.sampler.type = SamplerKind::ZSobol;
  ro.seed = 99;
  const Image ref = render(*scene, ro).image;
  RenderOptions o = ro;
  o.spp = 64;
  o.seed = 1;
  o.target_error = 1e-12;
  const RenderResult r = render(*scene, o);
  const double measured = relmse(r.image, ref), ratio = r.stats.estimated_relmse / measured;
  std::printf("zsobol: estimated relMSE %.5f, measured %.5f\n", r.stats.estimated_relmse, measured);
  EXPECT_LT(ratio, 1.5);
  EXPECT_GT(ratio, 1.0 / 1.5);
}

// The render stops once the estimate is below the target: the measured
// error is at most 10% above it, with samples spread unevenly. (Targets
// the box reaches in its first passes spread nothing: with the path
// tracer's roulette at 2, 0.008 took 64 spp everywhere.)
TEST(AdaptiveSampling, StopsAtTheTargetError) {
  if (LANTERN_ASAN) GTEST_SKIP() << "a reference at 8192 spp";
  auto scene = shipped("cornell-box.pbrt");
  const Image ref = reference(*scene, "path", 8192);
  for (double target : {0.004, 0.002}) {  // (the reference at 8192 spp adds under 0.00005)
    RenderOptions o = small("path", 1 << 16);
    o.target_error = target;
    const RenderResult r = render(*scene, o);
    EXPECT_FALSE(r.interrupted);
    // (The render stops when the estimate at the end of pass p - 2 is
    // below the target; the final one, with pass p - 1's samples, may be
    // a little above it: 0.0043 for 0.004.)
    EXPECT_LT(r.stats.estimated_relmse, 1.1 * target);
    EXPECT_LT(relmse(r.image, ref), 1.1 * target) << target;
    EXPECT_GT(r.stats.max_spp, 2 * r.stats.min_spp) << "samples should go where the error is";
    EXPECT_LT(r.stats.max_spp, 1u << 16);
    std::printf("  target %g: estimated %g, measured %g, spp %u-%u\n", target, r.stats.estimated_relmse,
                relmse(r.image, ref), r.stats.min_spp, r.stats.max_spp);
  }
}

// A budget of a mean N spp is spent to the block (16 pixels of a 16-sample
// pass), never over, and where it pays: in a room lit by a spot, where the
// pixels the spot's light reaches through one bounce are far noisier than
// the rest, the image's relMSE against a reference is below half of
// uniform sampling's at the same samples (over two seeds each; measured
// 0.12 and 0.11 against 0.57 and 0.62).
TEST(AdaptiveSampling, BudgetIsSpentWhereItPays) {
  if (LANTERN_ASAN) GTEST_SKIP() << "a reference at 1024 spp";
  auto scene = shipped("spotlit-room.pbrt");
  const Image ref = reference(*scene, "path", 1024);
  double adaptive = 0.0, uniform = 0.0;
  for (uint64_t seed = 1; seed <= 2; ++seed) {
    RenderOptions o = small("path", 128);
    o.seed = seed;
    const RenderResult u = render(*scene, o);
    o.adaptive = true;
    const RenderResult a = render(*scene, o);
    EXPECT_LE(a.stats.samples, 128u * 32u * 32u);
    EXPECT_GT(a.stats.samples, 128u * 32u * 32u - 16u * 16u);
    EXPECT_GT(a.stats.max_spp, 2 * a.stats.min_spp) << "samples should go where the error is";
    adaptive += relmse(a.image, ref);
    uniform += relmse(u.image, ref);
  }
  EXPECT_LT(adaptive, 0.5 * uniform);
}

double mse(const Image& a, const Image& ref) {
  double e = 0.0;
  for (size_t k = 0; k < a.rgb.size(); ++k)
    e += (double(a.rgb[k]) - double(ref.rgb[k])) * (double(a.rgb[k]) - double(ref.rgb[k]));
  return e / double(a.rgb.size());
}

// A budget lowers the MSE as well as the relMSE: blocks are chosen by
// their variance over sqrt(I^2 + 0.01) (ErrorMeasure::Balanced). On the
// Cornell box, whose bright pixels (the light's edges) hold much of the MSE
// and little of the relMSE, choosing by relMSE's own measure gave those
// pixels few samples: over four seeds at 64 x 64 it left 0.96 of uniform
// sampling's MSE and 0.97 of its relMSE; the balanced measure 0.60 and
// 0.78 (against a reference of 2048 spp).
//
// The reference has 512 spp, and its own error is taken out of both: a
// render's error against it is the render's own plus the reference's,
// and with independent samples the reference's is uniform sampling's at
// 128 spp times 128 / 512. So uniform's own is 4/5 of what it measures,
// and the reference's 1/5 of it.
TEST(AdaptiveSampling, BudgetLowersMseAndRelMse) {
  if (LANTERN_ASAN) GTEST_SKIP() << "a reference at 512 spp";
  auto scene = shipped("cornell-box.pbrt");
  constexpr int kSpp = 128, kReferenceSpp = 512;
  RenderOptions ro = small("path", kReferenceSpp);
  ro.width = ro.height = 64;  // (the light's edges are more of the image at 32 x 32)
  ro.seed = 99;
  const Image ref = render(*scene, ro).image;
  double mse_adaptive = 0.0, mse_uniform = 0.0, rel_adaptive = 0.0, rel_uniform = 0.0;
  for (uint64_t seed = 1; seed <= 4; ++seed) {
    RenderOptions o = small("path", kSpp);
    o.width = o.height = 64;
    o.seed = seed;
    const Image u = render(*scene, o).image;
    o.adaptive = true;
    const Image a = render(*scene, o).image;
    mse_adaptive += mse(a, ref), mse_uniform += mse(u, ref);
    rel_adaptive += relmse(a, ref), rel_uniform += relmse(u, ref);
  }
  constexpr double kReferenceShare = double(kSpp) / double(kSpp + kReferenceSpp);  // (of uniform's measured error)
  const double mse_reference = kReferenceShare * mse_uniform, rel_reference = kReferenceShare * rel_uniform;
  mse_adaptive -= mse_reference, mse_uniform -= mse_reference;
  rel_adaptive -= rel_reference, rel_uniform -= rel_reference;
  std::printf("  MSE %.3g of uniform's, relMSE %.3g\n", mse_adaptive / mse_uniform, rel_adaptive / rel_uniform);
  EXPECT_LT(mse_adaptive, 0.7 * mse_uniform);
  EXPECT_LT(rel_adaptive, 0.9 * rel_uniform);
}

// Where no block's estimate asks for more (no light: every estimate is 0),
// the budget is spent evenly instead of on passes that render nothing.
TEST(AdaptiveSampling, ABlackImageSpendsItsBudgetEvenly) {
  auto scene = load_scene_from_string("LookAt 0 0 -5  0 0 0  0 1 0\nCamera \"perspective\"\nWorldBegin\n"
                                      "Shape \"sphere\" \"float radius\" 1\n",
                                      "black.pbrt");
  RenderOptions o = small("path", 64);
  o.width = o.height = 16;
  o.adaptive = true;
  const RenderResult r = render(*scene, o);
  EXPECT_EQ(r.stats.samples, 64u * 16u * 16u);
  EXPECT_EQ(r.stats.min_spp, 64u);
  EXPECT_EQ(r.stats.max_spp, 64u);
}

// What stops sampling depends on the samples, yet the image is unbiased:
// region means over independent renders against a reference's, for a
// target and for a budget.
TEST(AdaptiveSampling, MeansMatchAReference) {
  auto scene = shipped("cornell-box.pbrt");
  RenderOptions ro = small("path", LANTERN_ASAN ? 256 : 2048);
  ro.seed = 99;
  const std::vector<Region> regions = {{0, 0, 16, 16}, {16, 0, 16, 16}, {0, 16, 16, 16}, {16, 16, 16, 16}};
  const RegionStats ref = stats_of({render(*scene, ro).image}, regions);
  for (bool budget : {false, true}) {
    RenderOptions o = small("path", 1 << 16);
    if (budget) {
      o.adaptive = true;
      o.spp = 256;  // (a quarter under the sanitizers, still above the 32 a budget needs)
    } else {
      o.target_error = LANTERN_ASAN ? 0.02 : 0.004;
    }
    const RegionStats adaptive = stats_of(render_runs(*scene, o, 6, 1), regions);
    for (size_t g = 0; g < regions.size(); ++g)
      for (size_t c = 0; c < 3; ++c)
        EXPECT_LT(std::fabs(adaptive.mean[g][c] - ref.mean[g][c]),
                  4.5 * adaptive.std_error[g][c] + 0.01 * ref.mean[g][c])
            << (budget ? "budget" : "target") << ", region " << g << " channel " << c;
  }
}

// Decisions read only each block's own sums and measurements the film
// keeps: the same image on one thread and two, and after being stopped and
// resumed, bit for bit.
TEST(AdaptiveSampling, SameImageAcrossThreadsAndResumes) {
  auto scene = shipped("cornell-box.pbrt");
  for (bool budget : {false, true}) {
    RenderOptions o = small("bdpt", 512);
    o.wave_size = 128;  // many waves, so stops fall inside passes
    if (budget) {
      o.adaptive = true;
      o.spp = LANTERN_ASAN ? 48 : 96;  // (under the sanitizers, a checkpoint a wave is slow)
    } else {
      o.target_error = 0.01;
    }
    // (The resumes below alternate one thread and two: under the
    // sanitizers they stand for this check too.)
    if (!LANTERN_ASAN) expect_thread_invariant(*scene, o, {"path", "bdpt"});
    expect_resumes_to_the_straight_image(*scene, o, "lantern_adaptive_resume.ckpt", 7, 11, 3,
                                         budget ? "budget" : "target");
  }
}

TEST(AdaptiveSampling, RefusesWhatItCannotDecide) {
  auto scene = shipped("cornell-box.pbrt");
  RenderOptions o = small("path", 4);
  o.target_error = 0.01;
  o.share_count = 2;
  EXPECT_THROW(render(*scene, o), std::invalid_argument);
  // A budget below the first two passes' 32 samples a pixel.
  o = small("path", 16);
  o.adaptive = true;
  EXPECT_THROW(render(*scene, o), std::invalid_argument);
}

}  // namespace
}  // namespace lantern
