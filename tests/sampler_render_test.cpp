// Every sampler in whole renders: the path tracer, bdpt and the light
// tracer still agree in the mean (changing the sample pattern must change
// noise only), and images stay bit-identical on 1 and 2 threads.
#include <gtest/gtest.h>

#include "lantern/render.h"
#include "lantern/scene.h"
#include "sanitizer.h"
#include "stat_compare.h"

namespace lantern {
namespace {

constexpr double kSamplerMaxZ = 5.0;  // as in bdpt_test.cpp
constexpr int kSamplerRuns = 10;

const std::vector<Region> kSamplerCornellRegions = {
    {0, 0, 32, 32}, {0, 0, 8, 8}, {12, 4, 8, 8}, {4, 20, 8, 8}, {20, 20, 8, 8}};

RegionStats sampler_stats(const Scene& scene, const char* sampler, const char* integrator, int spp) {
  RenderOptions o;
  o.sampler.type = parse_sampler(sampler);
  o.integrator = parse_integrator(integrator);
  o.spp = spp;
  o.maxdepth = 6;
  o.width = o.height = 32;
  return stats_of(render_runs(scene, o, kSamplerRuns, 500), kSamplerCornellRegions);
}

class SamplerRender : public ::testing::TestWithParam<const char*> {};

TEST_P(SamplerRender, PathBdptAndLightTracingAgree) {
  // The renders differ between samplers only in the values they read,
  // which sampler_test.cpp checks under the sanitizers; one sampler's
  // renders cover the integrators' code there.
  if (LANTERN_ASAN && std::string(GetParam()) != "zsobol") GTEST_SKIP() << "zsobol's covers the sanitized suite";
  auto scene = load_scene(std::string(LANTERN_SOURCE_DIR) + "/scenes/cornell-box.pbrt");
  auto path = sampler_stats(*scene, GetParam(), "path", 16);
  auto bdpt = sampler_stats(*scene, GetParam(), "bdpt", 16);
  auto lt = sampler_stats(*scene, GetParam(), "lt", 16);
  EXPECT_LT(max_z(bdpt, path), kSamplerMaxZ);
  EXPECT_LT(max_z(lt, path), kSamplerMaxZ);
}

TEST_P(SamplerRender, SameImageWithOneOrTwoThreads) {
  auto scene = load_scene(std::string(LANTERN_SOURCE_DIR) + "/scenes/caustics.pbrt");
  RenderOptions o;
  o.sampler.type = parse_sampler(GetParam());
  o.spp = 4;
  o.width = 48;
  o.height = 36;
  o.wave_size = 256;  // many waves, so the two threads interleave
  expect_thread_invariant(*scene, o, {"path", "bdpt", "lt"});
}

INSTANTIATE_TEST_SUITE_P(Samplers, SamplerRender,
                         ::testing::Values("independent", "stratified", "halton", "sobol", "paddedsobol", "zsobol"));

}  // namespace
}  // namespace lantern
