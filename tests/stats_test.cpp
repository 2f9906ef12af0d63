// The render's own measurements against counts they must equal: in a closed
// scene every ray hits, so vertices equal rays; every subpath ends exactly
// once; timing is reported only when asked for.
#include <gtest/gtest.h>


#include <cstdio>

#include "accel/ray_dump.h"
#include "accel/ray_stream.h"
#include "lantern/render.h"
#include "lantern/scene.h"

namespace lantern {
namespace {

uint64_t sum_ends(const std::vector<std::pair<std::string, uint64_t>>& ends) {
  uint64_t n = 0;
  for (const auto& e : ends) n += e.second;
  return n;
}

TEST(RenderStats, CountsAgreeInAClosedScene) {
  auto scene = load_scene(std::string(LANTERN_SOURCE_DIR) + "/scenes/lantern.pbrt");
  for (const char* integrator : {"path", "bdpt", "lt"}) {
    RenderOptions o;
    o.integrator = parse_integrator(integrator);
    o.spp = 2;
    o.width = 40;
    o.height = 30;
    o.maxdepth = 6;
    o.collect_stats = true;
    RenderStats s = render(*scene, o).stats;
    const bool eye = std::string(integrator) != "lt", light = std::string(integrator) != "path";
    EXPECT_EQ(s.samples, 40u * 30u * 2u) << integrator;
    EXPECT_EQ(s.eye_vertices, eye ? s.camera_rays + s.extension_rays : 0u) << integrator;
    EXPECT_EQ(sum_ends(s.eye_ends), eye ? s.samples : 0u) << integrator;
    EXPECT_EQ(s.light_paths, light ? s.samples : 0u) << integrator;
    EXPECT_EQ(s.light_vertices, s.light_rays) << integrator;
    // Light subpaths that never left the light (no emission sample) end nowhere.
    EXPECT_LE(sum_ends(s.light_ends), s.light_paths) << integrator;
    if (light) EXPECT_GT(sum_ends(s.light_ends), s.light_paths * 9 / 10) << integrator;
    EXPECT_TRUE(s.timed);
    double stage_sum = 0.0;
    for (const auto& st : s.stage_seconds) stage_sum += st.second;
    EXPECT_GT(stage_sum, 0.0) << integrator;
    EXPECT_GT(s.camera_ray_seconds + s.light_ray_seconds, 0.0) << integrator;
    EXPECT_GT(s.wave_pool_bytes, 0u);
    EXPECT_GE(s.threads, 1);
  }
}

// The rays actually handed to Embree, read back from a `--dump-rays` file,
// per kind, against the render's counters.
TEST(RenderStats, RayCountsMatchTheRaysGivenToEmbree) {
  auto scene = load_scene(std::string(LANTERN_SOURCE_DIR) + "/scenes/cornell-box.pbrt");
  const std::string path = ::testing::TempDir() + "/lantern_stats_test_rays.bin";
  RenderOptions o;
  o.integrator = Integrator::Bdpt;
  o.spp = 2;
  o.width = o.height = 24;
  o.dump_rays = path;
  RenderStats s = render(*scene, o).stats;
  uint64_t count[4] = {0, 0, 0, 0};
  for (const DumpedBatch& b : read_ray_dump(path)) count[b.kind] += b.rays.count;
  EXPECT_EQ(count[size_t(RayKind::Camera)], s.camera_rays);
  EXPECT_EQ(count[size_t(RayKind::Extension)], s.extension_rays);
  EXPECT_EQ(count[size_t(RayKind::LightExtension)], s.light_rays);
  EXPECT_EQ(count[size_t(RayKind::Shadow)], s.shadow_rays);
  EXPECT_GT(s.shadow_rays, 0u);
  std::remove(path.c_str());
}

// Next-event estimation counts one light sample per non-specular eye vertex
// (path; bdpt's s = 1); on a diffuse floor under a point light every sample
// is unoccluded, and with the light shut in a box none is (from the box's
// outside the light is behind the surface: a zero sample).
TEST(RenderStats, NextEventCountsUnoccludedLightSamples) {
  const std::string head = R"(LookAt 0 3 -3  0 0 0  0 1 0
Camera "perspective" "float fov" 60
WorldBegin
LightSource "point" "rgb I" [5 5 5] "point3 from" [0 2 0]
Shape "bilinearmesh" "point3 P" [-9 0 -9  9 0 -9  -9 0 9  9 0 9]
)";
  const std::string box = R"(Shape "trianglemesh" "point3 P" [-.3 1.7 -.3  .3 1.7 -.3  .3 1.7 .3  -.3 1.7 .3
                                 -.3 2.3 -.3  .3 2.3 -.3  .3 2.3 .3  -.3 2.3 .3]
  "integer indices" [0 1 2 0 2 3  4 6 5 4 7 6  0 4 5 0 5 1  1 5 6 1 6 2  2 6 7 2 7 3  3 7 4 3 4 0]
)";
  for (const char* integrator : {"path", "bdpt"}) {
    RenderOptions o;
    o.integrator = parse_integrator(integrator);
    o.spp = 1;
    o.width = 16;
    o.height = 16;
    o.maxdepth = 1;  // the floor only: no vertex beyond the first
    RenderStats open = render(*load_scene_from_string(head, "open.pbrt"), o).stats;
    EXPECT_EQ(open.light_samples, open.eye_vertices) << integrator;
    EXPECT_EQ(open.light_samples_unoccluded, open.light_samples) << integrator;
    RenderStats shut = render(*load_scene_from_string(head + box, "shut.pbrt"), o).stats;
    EXPECT_GT(shut.light_samples, 0u) << integrator;
    EXPECT_EQ(shut.light_samples_unoccluded, 0u) << integrator;
  }
}

TEST(RenderStats, NoTimingUnlessAsked) {
  auto scene = load_scene(std::string(LANTERN_SOURCE_DIR) + "/scenes/cornell-box.pbrt");
  RenderOptions o;
  o.spp = 1;
  o.width = o.height = 16;
  RenderStats s = render(*scene, o).stats;
  EXPECT_FALSE(s.timed);
  EXPECT_TRUE(s.stage_seconds.empty());
  EXPECT_EQ(s.camera_ray_seconds, 0.0);
}

TEST(SceneInfo, ReportsContentsAndBvh) {
  auto scene = load_scene(std::string(LANTERN_SOURCE_DIR) + "/scenes/cornell-box.pbrt");
  SceneInfo info = scene_info(*scene);
  EXPECT_GT(info.triangles, 10u);
  EXPECT_EQ(info.lights, 2u);  // the quad light's two triangles
  EXPECT_GT(info.bvh_bytes, 0);
  EXPECT_GE(info.bvh_peak_bytes, info.bvh_bytes);
  EXPECT_GT(info.geometry_bytes, info.triangles * 12);
}

}  // namespace
}  // namespace lantern
