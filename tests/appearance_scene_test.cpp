// The shipped scene with every appearance feature (textures on many
// parameters, alpha cutouts, bump maps, a mix material) renders the same
// with path tracing, bidirectional path tracing and light tracing.
#include <gtest/gtest.h>

#include "stat_compare.h"

namespace lantern {
namespace {

TEST(AppearanceScene, PathBdptAndLightTracingAgree) {
  auto scene = load_scene(std::string(LANTERN_SOURCE_DIR) + "/scenes/appearance.pbrt");
  const int w = 24, h = 16;
  const std::vector<Region> regions = {{0, 0, w, h}, {0, 8, 12, 8}, {12, 8, 12, 8}, {16, 0, 8, 8}, {4, 0, 8, 8}};
  auto path = render_stats(*scene, "path", w, h, 64, 12, regions);
  auto bdpt = render_stats(*scene, "bdpt", w, h, 16, 12, regions);
  EXPECT_LT(max_z(bdpt, path), 4.5);
  // Light tracing cannot see the sky directly (its light subpaths start at
  // infinity), and its estimate of the balls' sun highlights is heavy-tailed
  // (a z statistic over 12 runs is unreliable there): the floor's bottom rows
  // and the middle of the wall.
  const std::vector<Region> lt_regions = {{3, 13, 17, 3}, {6, 2, 12, 4}};
  auto path_lt = render_stats(*scene, "path", w, h, 64, 12, lt_regions);
  auto lt = render_stats(*scene, "lt", w, h, 32, 12, lt_regions);
  EXPECT_LT(max_z(lt, path_lt), 4.5);
}

// Textures, alpha, bump maps and mix decide everything from hashes of their
// arguments, so the image does not depend on the thread count.
TEST(AppearanceScene, BitIdenticalAcrossThreads) {
  auto scene = load_scene(std::string(LANTERN_SOURCE_DIR) + "/scenes/appearance.pbrt");
  RenderOptions o;
  o.spp = 2;
  o.width = 48;
  o.height = 32;
  expect_thread_invariant(*scene, o, {"path", "bdpt"});
}

}  // namespace
}  // namespace lantern
