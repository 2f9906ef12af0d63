// pbrt-v4's uniformgrid and rgbgrid media: the density integral along rays against
// closed forms and against a brute-force sum, distance sampling against
// the integral it inverts, transmittance through a grid slab in a render,
// the three integrators on a smoke blob, pbrt-v4's image of it, and bad
// grids refused.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>

#include "expect_error.h"
#include "lantern/render.h"
#include "lantern/scene.h"
#include "media_scenes.h"
#include "medium/grid_density.h"
#include "sanitizer.h"
#include "stat_compare.h"

namespace lantern {
namespace {

DensityGrid unit_box_grid(int n, float (*value)(int x, int y, int z)) {
  DensityGrid g;
  g.nx = g.ny = g.nz = n;
  for (int z = 0; z < n; ++z)
    for (int y = 0; y < n; ++y)
      for (int x = 0; x < n; ++x) g.values.push_back(value(x, y, z));
  return g;
}

// Samples sit at cell centres and the density falls to zero half a cell
// outside them (pbrt-v4's SampledGrid), so across a box of n constant
// samples an axis-parallel ray through the middle sees n - 1 cells of 1 and
// two half cells that ramp from 1/2 to 1: n - 1/4 cells in all.
TEST(GridDensity, ConstantGridIntegratesWithItsEdgeRamps) {
  DensityGrid g = unit_box_grid(4, [](int, int, int) { return 1.f; });
  float t_hit;
  EXPECT_NEAR(g.integrate(Vec3(-1, 0.5f, 0.5f), Vec3(1, 0, 0), 0.f, 10.f, -1.f, &t_hit), 3.75f / 4.f, 1e-6f);
  EXPECT_EQ(t_hit, kInfinity);
  EXPECT_NEAR(g.density(Vec3(0.f, 0.5f, 0.5f)), 0.5f, 1e-6f);  // on the face
  EXPECT_NEAR(g.density(Vec3(0.5f, 0.5f, 0.5f)), 1.f, 1e-6f);
}

// Samples equal to their x index: the density is x itself between the
// first and last sample, 0 before it, and falls from n - 1 to (n - 1) / 2
// over the last half cell: (n-1)^2/2 + 3(n-1)/8 cells.
TEST(GridDensity, LinearGridIntegratesExactly) {
  DensityGrid g = unit_box_grid(4, [](int x, int, int) { return float(x); });
  float t_hit;
  EXPECT_NEAR(g.integrate(Vec3(-1, 0.5f, 0.5f), Vec3(1, 0, 0), 0.f, 10.f, -1.f, &t_hit), (4.5f + 1.125f) / 4.f, 1e-5f);
}

// Any ray through a random grid under a rotation, scale and shift: the
// exact integral against a fine midpoint sum of the density, and the
// sampled point against the integral it inverts.
TEST(GridDensity, RandomRaysMatchABruteForceSumAndSamplingInvertsIt) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> u(0.f, 1.f);
  DensityGrid g;
  g.nx = 5, g.ny = 3, g.nz = 4;
  for (int i = 0; i < 60; ++i) g.values.push_back(u(rng) < 0.2f ? 0.f : 3.f * u(rng));
  g.p0 = Vec3(-1.f, 0.f, 2.f);
  g.p1 = Vec3(1.f, 0.5f, 3.f);
  const Mat4 render_from_medium = glm::translate(glm::rotate(Mat4(1.f), 0.7f, Vec3(1, 2, 3)), Vec3(0.3f, -0.2f, 0.1f));
  g.medium_from_render = glm::inverse(render_from_medium);
  for (int k = 0; k < 50; ++k) {
    const Vec3 target_m(g.p0 + (g.p1 - g.p0) * Vec3(u(rng), u(rng), u(rng)));
    const Vec3 from_m(target_m + 3.f * glm::normalize(Vec3(u(rng) - 0.5f, u(rng) - 0.5f, u(rng) - 0.5f)));
    const Vec3 o = Vec3(render_from_medium * Vec4(from_m, 1.f));
    const Vec3 d = glm::normalize(Vec3(render_from_medium * Vec4(target_m, 1.f)) - o);
    float t_hit;
    const float exact = g.integrate(o, d, 0.f, 6.f, -1.f, &t_hit);
    double sum = 0.0;
    const int steps = 200000;
    for (int s = 0; s < steps; ++s) sum += g.density(o + d * (6.f * (s + 0.5f) / steps));
    EXPECT_NEAR(exact, sum * 6.0 / steps, 2e-4 + 2e-4 * exact) << "ray " << k;
    if (exact > 0.f) {
      const float want = exact * u(rng);
      ASSERT_EQ(g.integrate(o, d, 0.f, 6.f, want, &t_hit), want);
      ASSERT_LT(t_hit, 6.f);
      EXPECT_NEAR(g.integrate(o, d, 0.f, t_hit, -1.f, &t_hit), want, 1e-4f + 1e-4f * want) << "ray " << k;
    }
  }
}

// The cells found empty are skipped (DensityGrid::occupied): integrals and
// sampled points are those of the grid that reads every cell's samples,
// bit for bit, on rays through a sparse random grid (most cells empty, some
// at the box's faces), and a grid with no sample set has no cell set.
TEST(GridDensity, SkippingEmptyCellsChangesNothing) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> u(0.f, 1.f);
  DensityGrid plain;
  plain.nx = 7, plain.ny = 5, plain.nz = 6;
  for (int i = 0; i < 7 * 5 * 6; ++i) plain.values.push_back(u(rng) < 0.9f ? 0.f : 2.f * u(rng));
  plain.p0 = Vec3(-1.f, 0.f, 0.f);
  plain.p1 = Vec3(1.f, 1.f, 2.f);
  DensityGrid skipping = plain;
  skipping.find_occupied_cells();
  int nonzero = 0;
  for (int k = 0; k < 2000; ++k) {
    const Vec3 target(plain.p0 + (plain.p1 - plain.p0) * Vec3(u(rng), u(rng), u(rng)));
    const Vec3 o = target + 4.f * glm::normalize(Vec3(u(rng) - 0.5f, u(rng) - 0.5f, u(rng) - 0.5f));
    const Vec3 d = glm::normalize(target - o);
    float hit_a, hit_b;
    const float a = plain.integrate(o, d, 0.f, 8.f, -1.f, &hit_a), b = skipping.integrate(o, d, 0.f, 8.f, -1.f, &hit_b);
    ASSERT_EQ(a, b) << "ray " << k;
    nonzero += a > 0.f;
    if (a > 0.f) {
      const float want = a * u(rng);
      plain.integrate(o, d, 0.f, 8.f, want, &hit_a);
      skipping.integrate(o, d, 0.f, 8.f, want, &hit_b);
      ASSERT_EQ(hit_a, hit_b) << "ray " << k;
    }
  }
  EXPECT_GT(nonzero, 200);  // (the test sees occupied cells, not only empty ones)
  DensityGrid empty = plain;
  std::fill(empty.values.begin(), empty.values.end(), 0.f);
  empty.find_occupied_cells();
  for (uint64_t w : empty.occupied) EXPECT_EQ(w, 0u);
}

// A slab of grid medium (constant samples; 4 along z over 2 units: 1.875
// units of density on the axis) before an emitter of radiance 1, at
// maxdepth 0: each pixel's expectation is exp(-sigma_t D / cos) on its ray.
TEST(GridMedium, SlabTransmittanceInARender) {
  std::string density;
  for (int i = 0; i < 8 * 8 * 4; ++i) density += "1 ";
  const std::string text = slab_scene(R"(MakeNamedMedium "slab" "string type" "uniformgrid"
  "rgb sigma_a" [ 0.2 0.4 0.8 ] "rgb sigma_s" [ 0.2 0.2 0.2 ]
  "point3 p0" [ -10 -10 1 ] "point3 p1" [ 10 10 3 ] "integer nx" 8 "integer ny" 8 "integer nz" 4
  "float density" [ )" + density + " ]");
  auto scene = load_scene_from_string(text, "slab.pbrt", {});
  RenderOptions o;
  o.integrator = Integrator::Path;
  o.width = o.height = 16;
  o.maxdepth = 0;
  const RegionStats st = stats_of(render_runs(*scene, [&] { o.spp = 64; return o; }(), 4, 1), {{0, 0, 16, 16}});
  const double sigma_t[3] = {0.4, 0.6, 1.0}, half = std::tan(5.0 * kPi / 180.0);
  for (int c = 0; c < 3; ++c) {
    double sum = 0.0;
    for (int y = 0; y < 64; ++y)
      for (int x = 0; x < 64; ++x) {
        const double fx = (2.0 * (x + 0.5) / 64 - 1.0) * half, fy = (2.0 * (y + 0.5) / 64 - 1.0) * half;
        sum += std::exp(-sigma_t[c] * 1.875 * std::sqrt(1.0 + fx * fx + fy * fy));
      }
    const double expected = sum / (64.0 * 64.0);
    EXPECT_LT(std::fabs(st.mean[0][size_t(c)] - expected), 4.0 * st.std_error[0][size_t(c)] + 2e-3 * expected)
        << "channel " << c << ": " << st.mean[0][size_t(c)] << " against " << expected;
  }
}

TEST(GridMedium, IntegratorsAgreeOnASmokeBlob) {
  if (LANTERN_ASAN) GTEST_SKIP() << "the Release suite runs it";
  auto scene = load_scene(std::string(LANTERN_SOURCE_DIR) + "/perf/media/smoke-grid.pbrt");
  const std::vector<Region> regions = {{15, 6, 10, 10}, {0, 0, 40, 30}, {12, 18, 16, 6}};
  const RegionStats path = render_stats(*scene, "path", 40, 30, 64, 8, regions);
  const RegionStats bdpt = render_stats(*scene, "bdpt", 40, 30, 64, 8, regions);
  const RegionStats lt = render_stats(*scene, "lt", 40, 30, 128, 8, regions);
  EXPECT_LT(max_z(path, bdpt), 4.5);
  EXPECT_LT(max_z(bdpt, lt), 4.5);
}

TEST(GridMedium, ImagesDoNotDependOnThreads) {
  auto scene = load_scene(std::string(LANTERN_SOURCE_DIR) + "/perf/media/smoke-grid.pbrt");
  RenderOptions o;
  o.width = 40;
  o.height = 30;
  o.spp = 4;
  o.maxdepth = 8;
  expect_thread_invariant(*scene, o, {"path", "bdpt", "lt"});
}

// pbrt-v4 (a CPU Release build of its public source, volpath) rendered perf/media/smoke-grid.pbrt
// at 160x120 with 512 spp; its means of the blob (40x40 at 60,25), the
// whole image and the floor below (40x15 at 50,75), by oiiotool --cut
// ... --printstats.
TEST(GridMedium, SmokeBlobMatchesPbrt) {
  if (LANTERN_ASAN) GTEST_SKIP() << "the Release suite runs it";
  auto scene = load_scene(std::string(LANTERN_SOURCE_DIR) + "/perf/media/smoke-grid.pbrt");
  expect_matches_pbrt(*scene, 160, 120, 20, 32, 4, {{60, 25, 40, 40}, {0, 0, 160, 120}, {50, 75, 40, 15}},
                      {{0.121301, 0.112358, 0.099090}, {0.191820, 0.183958, 0.168390}, {0.325529, 0.314830, 0.290270}},
                      0.01);
}

// rgbgrid: the absorption given per sample (constant per channel: n - 1/4
// cells across, with the edge ramps), the scattering not given (1 times
// scale, throughout the box: no ramps).
TEST(RgbGrid, GivenAndConstantPartsIntegrate) {
  RgbGrid g;
  g.nx = g.ny = g.nz = 4;
  g.sigma_a.assign(64, RGB(1.f, 2.f, 4.f));
  g.constant_s = RGB(0.5f);
  float t_hit;
  const RGB depth = g.integrate(Vec3(-1, 0.5f, 0.5f), Vec3(1, 0, 0), 0.f, 10.f, 0, -1.f, &t_hit);
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(depth[c], 0.9375f * g.sigma_a[0][c] + 0.5f, 1e-5f) << c;
  RGB a, sc;
  g.at(Vec3(0.f, 0.5f, 0.5f), &a, &sc);  // on the face: half the samples, all of the constant
  EXPECT_NEAR(a[2], 2.f, 1e-5f);
  EXPECT_NEAR(sc[0], 0.5f, 1e-6f);
}

TEST(RgbGrid, RandomRaysMatchABruteForceSumAndSamplingInvertsIt) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> u(0.f, 1.f);
  RgbGrid g;
  g.nx = 3, g.ny = 4, g.nz = 2;
  for (int i = 0; i < 24; ++i) g.sigma_s.push_back(RGB(3.f * u(rng), u(rng) < 0.3f ? 0.f : 2.f * u(rng), u(rng)));
  g.constant_a = RGB(0.2f);
  g.p0 = Vec3(0.f, -1.f, 0.f);
  g.p1 = Vec3(1.f, 1.f, 0.5f);
  for (int k = 0; k < 30; ++k) {
    const Vec3 target(u(rng), 2.f * u(rng) - 1.f, 0.5f * u(rng));
    const Vec3 o = target + 2.f * glm::normalize(Vec3(u(rng) - 0.5f, u(rng) - 0.5f, u(rng) - 0.5f));
    const Vec3 d = glm::normalize(target - o);
    float t_hit;
    const RGB exact = g.integrate(o, d, 0.f, 5.f, 0, -1.f, &t_hit);
    RGB sum(0.f);
    const int steps = 100000;
    for (int s = 0; s < steps; ++s) {
      RGB a, sc;
      g.at(o + d * (5.f * (s + 0.5f) / steps), &a, &sc);
      sum += (a + sc) * (5.f / steps);
    }
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(exact[c], sum[c], 5e-4f + 5e-4f * exact[c]) << "ray " << k;
    const int c = k % 3;
    if (exact[c] > 0.f) {
      const float want = exact[c] * u(rng);
      const RGB reached = g.integrate(o, d, 0.f, 5.f, c, want, &t_hit);
      ASSERT_LT(t_hit, 5.f);
      EXPECT_NEAR(reached[c], want, 1e-5f + 1e-5f * want);
      const RGB again = g.integrate(o, d, 0.f, t_hit, 0, -1.f, &t_hit);
      for (int k2 = 0; k2 < 3; ++k2) EXPECT_NEAR(again[k2], reached[k2], 1e-4f + 1e-4f * reached[k2]) << "ray " << k;
    }
  }
}

TEST(RgbGrid, IntegratorsAgreeAndMatchPbrt) {
  if (LANTERN_ASAN) GTEST_SKIP() << "the Release suite runs it";
  auto scene = load_scene(std::string(LANTERN_SOURCE_DIR) + "/perf/media/rgb-grid.pbrt");
  const std::vector<Region> regions = {{15, 6, 10, 10}, {0, 0, 40, 30}, {12, 18, 16, 6}};
  const RegionStats path = render_stats(*scene, "path", 40, 30, 64, 8, regions);
  EXPECT_LT(max_z(path, render_stats(*scene, "bdpt", 40, 30, 64, 8, regions)), 4.5);
  EXPECT_LT(max_z(path, render_stats(*scene, "lt", 40, 30, 128, 8, regions)), 4.5);
  // pbrt-v4 (volpath, 160x120, 512 spp): the blob (40x40 at 60,25), the
  // whole image, the floor (40x15 at 50,75); oiiotool --cut ... --printstats.
  expect_matches_pbrt(*scene, 160, 120, 20, 16, 4, {{60, 25, 40, 40}, {0, 0, 160, 120}, {50, 75, 40, 15}},
                      {{0.073020, 0.069387, 0.054413}, {0.168109, 0.161429, 0.147265}, {0.179046, 0.167166, 0.155649}},
                      0.012);
}

TEST(GridMedium, BadGridsAreRefusedWithTheirLine) {
  const std::string head = "LookAt 0 0 0 0 0 1 0 1 0\nCamera \"perspective\"\nWorldBegin\n"
                           "MakeNamedMedium \"g\" \"string type\" \"uniformgrid\" ";
  expect_load_error(head + "\"integer nx\" 2 \"float density\" [ 1 ]\n", "a.pbrt",
                    {"a.pbrt:4", "has 1 values; expected nx * ny * nz = 2"});
  expect_load_error(head + "\"integer nx\" 100000 \"integer ny\" 100000 \"integer nz\" 100000 \"float density\" [ 1 ]\n",
                    "b.pbrt", {"b.pbrt:4", "expected nx * ny * nz = 1000000000000000"});
  expect_load_error(head + "\"float density\" [ -1 ]\n", "c.pbrt", {"c.pbrt:4", "finite and not negative"});
  expect_load_error(head + "\n", "d.pbrt", {"d.pbrt:4", "needs \"float density\""});
  expect_load_error(head + "\"float density\" [ 1 ] \"point3 p1\" [ 1 0 1 ]\n", "e.pbrt",
                    {"e.pbrt:4", "\"p0\" must lie below \"p1\""});
  expect_load_error(head + "\"float density\" [ 1 ] \"float temperature\" [ 900 900 ]\n", "f.pbrt",
                    {"f.pbrt:4", "has 2 values; expected as many as \"density\" (1)"});
  expect_load_error(head + "\"float density\" [ 1 ] \"float temperature\" [ 900 ] \"rgb Le\" [ 1 1 1 ]\n", "m.pbrt",
                    {"m.pbrt:4", "\"Le\" or \"temperature\", not both"});
  expect_load_error(head + "\"integer nx\" 2 \"float density\" [ 1 1 ] \"float Lescale\" [ 2 ]\n", "n.pbrt",
                    {"n.pbrt:4", "has 1 values; expected nx * ny * nz = 2"});
  expect_load_error(head + "\"float density\" [ 1 ] \"integer nx\" 0\n", "g.pbrt", {"g.pbrt:4", "at least 1"});
  const std::string rgb = "LookAt 0 0 0 0 0 1 0 1 0\nCamera \"perspective\"\nWorldBegin\n"
                          "MakeNamedMedium \"g\" \"string type\" \"rgbgrid\" ";
  expect_load_error(rgb + "\n", "h.pbrt", {"h.pbrt:4", "\"rgb sigma_a\" and/or \"rgb sigma_s\""});
  expect_load_error(rgb + "\"integer nx\" 2 \"rgb sigma_s\" [ 1 1 1 ]\n", "i.pbrt",
                    {"i.pbrt:4", "has 1 values; expected nx * ny * nz = 2"});
  expect_load_error(rgb + "\"float sigma_a\" [ 1 ]\n", "j.pbrt", {"j.pbrt:4", "expected \"rgb\" values"});
  expect_load_error(rgb + "\"rgb sigma_s\" [ 1e30 1 1 ] \"float scale\" 1e30\n", "l.pbrt",
                    {"l.pbrt:4", "times \"scale\" must be finite"});
  expect_load_error(rgb + "\"rgb sigma_s\" [ 1 1 1 ] \"rgb Le\" [ 1 0 0 ]\n", "k.pbrt",
                    {"k.pbrt:4", "with \"Le\" needs \"rgb sigma_a\""});
  expect_load_error(rgb + "\"rgb sigma_a\" [ 1 1 1 ] \"rgb Le\" [ 1 0 0  1 1 1 ]\n", "o.pbrt",
                    {"o.pbrt:4", "has 2 values; expected nx * ny * nz = 1"});
}

}  // namespace
}  // namespace lantern
