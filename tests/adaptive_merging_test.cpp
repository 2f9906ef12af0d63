// Adaptive sampling with vcm (integrator/run_passes.h's choose_adaptive):
// every pass traces all its light subpaths, takes camera samples only for
// the pixels that take it, and keeps its splats to those pixels, scaled by
// its own light paths. So each pixel averages whole passes of vcm, whose
// weights change from pass to pass (the merging radius shrinks): the
// image's means are uniform vcm's, and the render is as deterministic as
// any other.
#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "lantern/render.h"
#include "lantern/scene.h"
#include "sanitizer.h"
#include "stat_compare.h"
#include "stop_and_resume.h"

namespace lantern {
namespace {

std::shared_ptr<Scene> shipped_scene(const char* name) {
  return load_scene(std::string(LANTERN_SOURCE_DIR) + "/scenes/" + name);
}

RenderOptions small_vcm(int spp) {
  RenderOptions o;
  o.integrator = Integrator::Vcm;
  o.sampler.type = SamplerKind::Independent;  // (the half-buffer estimate assumes independent samples)
  o.spp = spp;
  o.width = 32;
  o.height = 32;
  o.maxdepth = 5;
  return o;
}

// The caustics scene: a 2 cm light over glass and gold on a diffuse floor,
// whose caustics vcm finds by light tracing and merging, and whose budget
// goes unevenly (40 to 952 samples a pixel at a mean of 256). Region means
// of adaptive vcm, to a budget and to a target, against uniform vcm's,
// within 4.5 standard errors and 2%: every adaptive scheme that decides
// from the samples it averages darkens pixels of rare bright paths (1.4%
// in the caustic's quarter over 24 renders, as much as bdpt's: docs/
// adaptive-sampling.md, "Where it is still wrong"). Splats kept in every
// pixel, whether it takes the pass or not, put the light tracing of passes
// a pixel skipped over the camera samples it took: z = 21, and the test
// fails.
TEST(AdaptiveMerging, MeansMatchUniformVcm) {
  auto scene = shipped_scene("caustics.pbrt");
  const std::vector<Region> regions = {
      {0, 0, 16, 16}, {16, 0, 16, 16}, {0, 16, 16, 16}, {16, 16, 16, 16}, {8, 8, 16, 16}};
  // Under the sanitizers, the code paths on fewer renders (the sanitized suite's time),
  // too few for the comparison: standard errors of 2 degrees of freedom.
  const int runs = LANTERN_ASAN ? 3 : 8;
  const RegionStats uniform = stats_of(render_runs(*scene, small_vcm(256), runs, 1), regions);
  for (bool budget : {true, false}) {
    RenderOptions o = small_vcm(budget ? 256 : 1 << 12);
    if (budget)
      o.adaptive = true;
    else
      o.target_error = LANTERN_ASAN ? 0.05 : 0.01;
    const RegionStats adaptive = stats_of(render_runs(*scene, o, runs, 101), regions);
    print_z(budget ? "adaptive vcm (budget) against uniform" : "adaptive vcm (target) against uniform",
            max_z_of(uniform, adaptive));
    if (!LANTERN_ASAN) expect_means_agree(uniform, adaptive, 0.02, budget ? "budget" : "target");
  }
}

// The samples do go where the estimate asks: a budget leaves some pixels
// at the first 32 samples and gives others several times the mean (a mean
// of at least 96, so that 32 is less than half of it).
TEST(AdaptiveMerging, BudgetGoesWhereItPays) {
  auto scene = shipped_scene("caustics.pbrt");
  RenderOptions o = small_vcm(LANTERN_ASAN ? 96 : 256);
  o.adaptive = true;
  const RenderResult r = render(*scene, o);
  EXPECT_EQ(r.stats.samples, uint64_t(o.spp) * 32u * 32u);
  EXPECT_LT(r.stats.min_spp, uint32_t(o.spp / 2));
  EXPECT_GT(r.stats.max_spp, uint32_t(2 * o.spp));
  EXPECT_GT(r.stats.estimated_relmse, 0.0);
}

// Decisions read only the film: the same image on one thread and two, and
// after being stopped and resumed, bit for bit; bpm and ppm (merging
// alone) too.
TEST(AdaptiveMerging, SameImageAcrossThreadsAndResumes) {
  auto scene = shipped_scene("caustics.pbrt");
  RenderOptions o = small_vcm(LANTERN_ASAN ? 40 : 64);
  o.wave_size = 256;  // four waves a pass, so stops fall inside passes
  o.adaptive = true;
  expect_thread_invariant(*scene, o, {"vcm", "bpm", "ppm"});
  expect_resumes_to_the_straight_image(*scene, o, "lantern_adaptive_vcm_resume.ckpt", 7, 23, 3);
}

// Film "spectral": the buckets take the pass's splats as the image does
// (Film::prepare_buckets). The caustics with four buckets, each bucket's
// mean over the pixels that do not see the 2 cm light (whose own pixels'
// values are a lottery at these samples): adaptive vcm's within 2% of
// uniform vcm's (measured within 0.2%). With the splats of the passes a
// pixel skipped kept in its buckets, 25% above, and the test fails.
TEST(AdaptiveMerging, SpectralBucketsTakeThePassesThePixelTakes) {
  std::ifstream in(std::string(LANTERN_SOURCE_DIR) + "/scenes/caustics.pbrt");
  std::stringstream text;
  text << in.rdbuf();
  std::string scene_text = text.str();
  const std::string film = "Film \"rgb\"";
  ASSERT_NE(scene_text.find(film), std::string::npos);
  scene_text.replace(scene_text.find(film), film.size(), "Film \"spectral\" \"integer nbuckets\" [ 4 ]");
  auto scene = load_scene_from_string(scene_text, "caustics-spectral.pbrt");
  auto render_buckets = [&](bool adaptive) {
    RenderOptions o = small_vcm(LANTERN_ASAN ? 64 : 256);
    o.sampler.type = SamplerKind::ZSobol;
    o.width = 48;
    o.height = 36;
    o.spectral = true;
    o.spectral_buckets = scene_settings(*scene).spectral_buckets;
    o.adaptive = adaptive;
    return render(*scene, o).image;
  };
  const Image uniform = render_buckets(false), adaptive = render_buckets(true);
  ASSERT_EQ(uniform.channel_names.size(), 4u);
  ASSERT_EQ(adaptive.channel_names.size(), 4u);
  const size_t pixels = size_t(uniform.width) * size_t(uniform.height);
  auto light_seen = [](const Image& img, size_t i) { return img.rgb[3 * i] + img.rgb[3 * i + 1] > 10.f; };
  for (size_t b = 0; b < 4; ++b) {
    double u = 0.0, a = 0.0;
    for (size_t i = 0; i < pixels; ++i)
      if (!light_seen(uniform, i) && !light_seen(adaptive, i))
        u += uniform.channels[4 * i + b], a += adaptive.channels[4 * i + b];
    std::printf("bucket %zu: uniform %.2f, adaptive %.2f\n", b, u, a);
    EXPECT_NEAR(a, u, 0.02 * u) << "bucket " << b;
  }
}

}  // namespace
}  // namespace lantern
