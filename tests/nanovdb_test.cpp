// pbrt-v4's "nanovdb" medium: a NanoVDB grid against the same samples as
// a uniformgrid (the exact integral and sampling of both), the skipping of
// empty blocks against a brute-force sum along random rays, the three
// integrators on a sparse two-blob grid, pbrt-v4's image of it, and bad
// files refused with their scene line.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <random>
#include <string>

#include "../perf/media/nvdb_blobs.h"
#include "expect_error.h"
#include "lantern/scene.h"
#include "medium/grid_density.h"
#include "medium/nanovdb_grid.h"
#include "media_scenes.h"
#include "sanitizer.h"
#include "stat_compare.h"

namespace lantern {
namespace {

// A file in this process's own temporary folder, removed at exit.
std::string vdb_temp_path(const std::string& name) {
  struct Folder {
    std::filesystem::path path =
        std::filesystem::temp_directory_path() / ("lantern-vdb-" + std::to_string(getpid()));
    Folder() { std::filesystem::create_directories(path); }
    ~Folder() {
      std::error_code ec;
      std::filesystem::remove_all(path, ec);
    }
  };
  static const Folder folder;
  return (folder.path / name).string();
}

// A 6^3 grid of voxel size h at index 0..5, random inside and with its
// outer layer stored as zeros, as a NanoVDB file and as a uniformgrid:
// samples at the same points, so the same trilinear density everywhere.
struct TwinGrids {
  VdbGrid vdb;
  DensityGrid dense;
};

TwinGrids make_twin_grids(const Mat4& medium_from_render) {
  const int n = 6;
  const double h = 0.25;
  std::mt19937 gen(3);
  std::uniform_real_distribution<float> u(0.f, 1.f);
  nanovdb::GridBuilder<float> builder(0.f);
  auto acc = builder.getAccessor();
  TwinGrids t;
  t.dense.nx = t.dense.ny = t.dense.nz = n;
  t.dense.p0 = Vec3(float(-0.5 * h));
  t.dense.p1 = Vec3(float((n - 0.5) * h));
  t.dense.medium_from_render = medium_from_render;
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        const bool edge = i == 0 || j == 0 || k == 0 || i == n - 1 || j == n - 1 || k == n - 1;
        const float v = edge || u(gen) < 0.2f ? 0.f : 3.f * u(gen);
        acc.setValue(nanovdb::Coord(i, j, k), v);
        t.dense.values.push_back(v);
      }
  const std::string path = vdb_temp_path("twin.nvdb");
  nanovdb::io::writeGrid(path, builder.getHandle<>(h, nanovdb::Vec3d(0.0), "density"));
  t.vdb = VdbGrid::load(path, "density", medium_from_render);
  return t;
}

TEST(NanoVdb, MatchesTheUniformGridOfTheSameSamples) {
  const Mat4 render_from_medium =
      glm::rotate(glm::translate(Mat4(1.f), Vec3(0.3f, -0.2f, 0.1f)), 0.6f, glm::normalize(Vec3(1, 2, 3)));
  const TwinGrids t = make_twin_grids(glm::inverse(render_from_medium));
  std::mt19937 gen(9);
  std::uniform_real_distribution<float> u(0.f, 1.f);
  for (int r = 0; r < 40; ++r) {
    const Vec3 target = Vec3(render_from_medium * Vec4(Vec3(u(gen), u(gen), u(gen)) * 1.25f, 1.f));
    const Vec3 o = target + 3.f * glm::normalize(Vec3(u(gen) - 0.5f, u(gen) - 0.5f, u(gen) - 0.5f));
    const Vec3 d = glm::normalize(target - o);
    float hit_a, hit_b;
    const float a = t.vdb.integrate(o, d, 0.f, 6.f, -1.f, &hit_a), b = t.dense.integrate(o, d, 0.f, 6.f, -1.f, &hit_b);
    EXPECT_NEAR(a, b, 1e-4f * std::max(1.f, b)) << "ray " << r;
    if (b > 0.2f) {  // the point where half the integral is reached
      t.vdb.integrate(o, d, 0.f, 6.f, 0.5f * b, &hit_a);
      t.dense.integrate(o, d, 0.f, 6.f, 0.5f * b, &hit_b);
      EXPECT_NEAR(hit_a, hit_b, 1e-4f) << "ray " << r;
    }
    const Vec3 p = o + d * (3.f * u(gen));
    EXPECT_NEAR(t.vdb.density(p), t.dense.density(p), 1e-4f);
  }
}

// The two-blob grid: most blocks are empty, and the integral along random
// rays (many through the empty part) equals a fine sum of the density.
TEST(NanoVdb, EmptyBlocksAreSkippedWithoutChangingTheIntegral) {
  const std::string path = vdb_temp_path("blobs.nvdb");
  nvdb_blobs::write(path);
  const VdbGrid g = VdbGrid::load(path, "density", Mat4(1.f));
  size_t total = 0;
  const size_t occupied = g.occupied_blocks(&total);
  EXPECT_GT(total, 0u);
  EXPECT_LT(occupied, total * 3 / 4) << occupied << " of " << total;
  std::mt19937 gen(4);
  std::uniform_real_distribution<float> u(0.f, 1.f);
  for (int r = 0; r < 25; ++r) {
    const Vec3 a(0.1f + 2.f * u(gen), 0.1f + 0.7f * u(gen), 0.1f + 0.7f * u(gen));
    const Vec3 b(0.1f + 2.f * u(gen), 0.1f + 0.7f * u(gen), 0.1f + 0.7f * u(gen));
    const Vec3 d = glm::normalize(b - a);
    const float len = glm::length(b - a);
    float unused;
    const double exact = g.integrate(a, d, 0.f, len, -1.f, &unused);
    const int steps = 20000;
    double sum = 0.0;
    for (int s = 0; s < steps; ++s) sum += g.density(a + d * ((s + 0.5f) / steps * len));
    sum *= len / steps;
    EXPECT_NEAR(exact, sum, 2e-3 * std::max(1.0, sum)) << "ray " << r;
  }
}

// The two-blob scene with the grid written beside it; burning: the
// variant with a temperature grid (nanovdb-burning.pbrt).
std::shared_ptr<Scene> blobs_scene(bool burning = false) {
  const std::string name = burning ? "burning.nvdb" : "blobs.nvdb";
  const std::string path = vdb_temp_path(name);
  if (burning) nvdb_blobs::write_burning(path);
  else nvdb_blobs::write(path);
  std::ifstream in(std::string(LANTERN_SOURCE_DIR) + (burning ? "/perf/media/nanovdb-burning.pbrt" : "/perf/media/nanovdb-blobs.pbrt"));
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const size_t at = text.find("\"" + name + "\"");
  EXPECT_NE(at, std::string::npos);
  text.replace(at, name.size() + 2, "\"" + path + "\"");
  return load_scene_from_string(text, burning ? "nanovdb-burning.pbrt" : "nanovdb-blobs.pbrt", {});
}

TEST(NanoVdb, IntegratorsAgree) {
  if (LANTERN_ASAN) GTEST_SKIP() << "the Release suite runs it";
  auto scene = blobs_scene();
  const std::vector<Region> regions = {{8, 10, 10, 9}, {26, 14, 6, 6}, {0, 0, 40, 30}};
  expect_medium_integrators_agree(*scene, regions);
}

TEST(NanoVdb, ImagesDoNotDependOnThreads) {
  auto scene = blobs_scene();
  expect_medium_thread_invariant(*scene);
}

// pbrt-v4 (a CPU Release build of its public source, volpath) rendered perf/media/nanovdb-blobs.pbrt
// (its grid written by lantern-make-nvdb) at 160x120 with 512 spp; its
// means of the left blob (40x35 at 30,40), the right one (25x25 at 105,55)
// and the whole image, by oiiotool --cut ... --printstats.
TEST(NanoVdb, MatchesPbrt) {
  if (LANTERN_ASAN) GTEST_SKIP() << "the Release suite runs it";
  auto scene = blobs_scene();
  expect_matches_pbrt(*scene, 160, 120, 20, 16, 4, {{30, 40, 40, 35}, {105, 55, 25, 25}, {0, 0, 160, 120}},
                      {{0.172635, 0.165124, 0.150776}, {0.297946, 0.285689, 0.261965}, {0.186422, 0.179014, 0.164111}},
                      0.01);
}

TEST(NanoVdb, BadFilesAreRefusedWithTheirLine) {
  const std::string good = vdb_temp_path("good.nvdb");
  nvdb_blobs::write(good);
  const std::string garbage = vdb_temp_path("garbage.nvdb"), cut = vdb_temp_path("cut.nvdb");
  std::ofstream(garbage) << "not a grid at all, but long enough to hold a header or two";
  {
    std::ifstream in(good, std::ios::binary);
    std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    std::ofstream(cut, std::ios::binary) << bytes.substr(0, bytes.size() / 2);
  }
  const std::string two = vdb_temp_path("two.nvdb");  // a density and a temperature grid
  {
    nanovdb::GridBuilder<float> a(0.f), b(0.f);
    a.getAccessor().setValue(nanovdb::Coord(0), 1.f);
    b.getAccessor().setValue(nanovdb::Coord(0), 1500.f);
    std::vector<nanovdb::GridHandle<nanovdb::HostBuffer>> handles;
    handles.push_back(a.getHandle<>(1.0, nanovdb::Vec3d(0.0), "density"));
    handles.push_back(b.getHandle<>(1.0, nanovdb::Vec3d(0.0), "temperature"));
    nanovdb::io::writeGrids(two, handles);
  }
  const std::string head = "LookAt 0 0 0 0 0 1 0 1 0\nCamera \"perspective\"\nWorldBegin\n"
                           "MakeNamedMedium \"v\" \"string type\" \"nanovdb\" ";
  auto file = [](const std::string& p) { return "\"string filename\" \"" + p + "\""; };
  expect_load_error(head + "\n", "a.pbrt", {"a.pbrt:4", "needs \"string filename\""});
  expect_load_error(head + file(vdb_temp_path("none.nvdb")) + "\n", "b.pbrt", {"b.pbrt:4", "cannot open"});
  expect_load_error(head + file(garbage) + "\n", "c.pbrt", {"c.pbrt:4", "not a NanoVDB file"});
  expect_load_error(head + file(cut) + "\n", "d.pbrt", {"d.pbrt:4", "cut short"});
  expect_load_error(head + file(good) + " \"string gridname\" \"smoke\"\n", "e.pbrt",
                    {"e.pbrt:4", "no grid named \"smoke\""});
  expect_load_error(head + file(two) + " \"float Lescale\" 1e39\n", "f.pbrt",
                    {"f.pbrt:4", "must be finite"});
  EXPECT_NO_THROW(load_scene_from_string(head + file(two) + " \"float Lescale\" 0\n", "g.pbrt", {}));
}

// The burning variant: the small blob is a black body of up to 2400 K.
TEST(NanoVdb, BurningBlobIsAVolumeLight) {
  auto scene = blobs_scene(true);
  ASSERT_EQ(scene->lights.volume.size(), 1u);
  expect_volume_light_integrates(*scene);
}

TEST(NanoVdb, BurningIntegratorsAgree) {
  if (LANTERN_ASAN) GTEST_SKIP() << "the Release suite runs it";
  auto scene = blobs_scene(true);
  expect_medium_integrators_agree(*scene, {{27, 15, 5, 5}, {25, 20, 10, 4}, {0, 0, 40, 30}});
}

// pbrt-v4 (volpath, 512 spp) rendered perf/media/nanovdb-burning.pbrt (its
// grids written by lantern-make-nvdb --burning) at 160x120; its means of
// the burning blob (20x20 at 108,60), the floor below it (40x16 at
// 100,82) and the whole image, by oiiotool --cut ... --printstats.
TEST(NanoVdb, BurningMatchesPbrt) {
  if (LANTERN_ASAN) GTEST_SKIP() << "the Release suite runs it";
  auto scene = blobs_scene(true);
  expect_matches_pbrt(*scene, 160, 120, 20, 16, 4, {{108, 60, 20, 20}, {100, 82, 40, 16}, {0, 0, 160, 120}},
                      {{0.922401, 0.469874, 0.290698}, {0.381585, 0.338394, 0.301476}, {0.202238, 0.183336, 0.164389}},
                      0.02);
  // With sampled wavelengths the fire is Planck's law itself, as pbrt-v4's
  // (within 0.7% of it per channel here).
  expect_matches_pbrt(*scene, 160, 120, 20, 16, 4, {{108, 60, 20, 20}, {100, 82, 40, 16}, {0, 0, 160, 120}},
                      {{0.922401, 0.469874, 0.290698}, {0.381585, 0.338394, 0.301476}, {0.202238, 0.183336, 0.164389}},
                      0.02, true);
}

}  // namespace
}  // namespace lantern
