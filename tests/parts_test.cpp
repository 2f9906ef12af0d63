// --part K/N and `lantern merge`: the parts of a render, rendered apart on
// any thread counts and added up, equal the render made in one go bit for
// bit; merge refuses what does not belong together, naming the file.
#include <gtest/gtest.h>

#include <cstdio>
#include <cstring>

#include "expect_error.h"
#include "film/merge_parts.h"
#include "lantern/render.h"
#include "lantern/scene.h"
#include "sanitizer.h"

namespace lantern {
namespace {

std::string part_file(int k, const std::string& tag = "") {
  const ::testing::TestInfo* t = ::testing::UnitTest::GetInstance()->current_test_info();
  std::string name = std::string(t->test_suite_name()) + "_" + t->name() + tag + "_" + std::to_string(k);
  for (char& c : name)
    if (c == '/') c = '_';
  return ::testing::TempDir() + "/lantern_" + name + ".part";
}

RenderOptions parts_render(const std::string& integrator) {
  RenderOptions o;
  o.integrator = parse_integrator(integrator);
  o.spp = 20;  // two passes, the second short
  o.width = 40;
  o.height = 30;
  o.maxdepth = 5;
  o.wave_size = 300;  // many units
  o.seed = 3;
  return o;
}

// Renders part k+1 of n into its file; returns the path.
std::string render_part(const Scene& scene, RenderOptions o, uint32_t k, uint32_t n, const std::string& tag = "",
                        const RenderHooks& hooks = {}) {
  o.share_index = k;
  o.share_count = n;
  o.film_path = part_file(int(k), tag);
  o.threads = 1 + int(k % 2);
  render(scene, o, hooks);
  return o.film_path;
}

bool identical_images(const Image& a, const Image& b) {
  return a.width == b.width && a.height == b.height &&
         std::memcmp(a.rgb.data(), b.rgb.data(), a.rgb.size() * sizeof(float)) == 0;
}

class Parts : public ::testing::TestWithParam<const char*> {};

TEST_P(Parts, MergeEqualsTheSingleRender) {
  auto scene = load_scene(std::string(LANTERN_SOURCE_DIR) + "/scenes/cornell-box.pbrt");
  const RenderOptions o = parts_render(GetParam());
  const RenderResult single = render(*scene, o);
  // Any N: with an even one, a part's waves in flight have numbers of the
  // same parity (a wave's output slot must not follow its number).
  for (uint32_t n : {2u, 3u, 4u}) {
    std::vector<std::string> files;
    for (uint32_t k = 0; k < n; ++k) files.push_back(render_part(*scene, o, k, n));
    std::swap(files.front(), files.back());  // any order
    MergedParts m = merge_parts(files, false);
    EXPECT_TRUE(m.complete);
    EXPECT_EQ(m.film.total_samples(), single.stats.samples) << n << " parts";
    EXPECT_EQ(m.film.light_paths(), single.stats.light_paths) << n << " parts";
    EXPECT_TRUE(identical_images(m.film.resolve(), single.image)) << n << " parts: the merged image differs";
    for (const std::string& f : files) std::remove(f.c_str());
  }
}

INSTANTIATE_TEST_SUITE_P(Integrators, Parts, ::testing::Values("path", "bdpt", "lt", "vcm"));

TEST(PartsMerge, RefusesWhatDoesNotBelong) {
  auto scene = load_scene(std::string(LANTERN_SOURCE_DIR) + "/scenes/cornell-box.pbrt");
  RenderOptions o = parts_render("path");
  o.spp = 48;  // three passes: every part covers every pixel
  const std::string p1 = render_part(*scene, o, 0, 3), p2 = render_part(*scene, o, 1, 3), p3 = render_part(*scene, o, 2, 3);
  RenderOptions other = o;
  other.seed = 4;
  const std::string seed4 = render_part(*scene, other, 1, 3, "seed");
  other = o;
  other.width = 41;
  const std::string wider = render_part(*scene, other, 1, 3, "wide");
  const std::string half = render_part(*scene, o, 1, 2, "half");
  auto error_of = [](const std::vector<std::string>& files) {
    try {
      merge_parts(files, false);
    } catch (const std::exception& e) {
      return std::string(e.what());
    }
    return std::string("(no error)");
  };
  auto expect_error = [&](const std::vector<std::string>& files, const std::string& file, const std::string& words) {
    const std::string e = error_of(files);
    EXPECT_NE(e.find(file), std::string::npos) << e;
    EXPECT_NE(e.find(words), std::string::npos) << e;
  };
  expect_error({p1, seed4, p3}, seed4, "\"seed=4\" where the first part has \"seed=3\"");
  expect_error({p1, wider, p3}, wider, "resolution=41x30");
  expect_error({p1, p2, p2, p3}, p2, "is part 2/3 again");
  expect_error({p1, half}, half, "is part 2/2, but");
  expect_error({p1, p3}, "", "part 2/3 is missing; merge the parts there are with --preview");
  expect_error({p1, p2, "/nonexistent/part"}, "/nonexistent/part", "cannot open");
  expect_error({std::string(LANTERN_SOURCE_DIR) + "/scenes/cornell-box.pbrt"}, "cornell-box.pbrt", "not a Lantern");

  // A preview of two of three parts: every pixel normalised by its own
  // samples, so the mean stays that of the full image.
  MergedParts preview = merge_parts({p1, p3}, true);
  EXPECT_FALSE(preview.complete);
  ASSERT_EQ(preview.missing.size(), 1u);
  EXPECT_NE(preview.missing[0].find("part 2/3 is missing"), std::string::npos);
  const Image full = merge_parts({p1, p2, p3}, false).film.resolve(), partial = preview.film.resolve();
  double mean_full = 0.0, mean_partial = 0.0;
  for (size_t i = 0; i < full.rgb.size(); ++i) {
    mean_full += full.rgb[i];
    mean_partial += partial.rgb[i];
  }
  EXPECT_NEAR(mean_partial / mean_full, 1.0, 0.05);
  EXPECT_GT(preview.film.min_samples_per_pixel(), 0u);
  for (const std::string& f : {p1, p2, p3, seed4, wider, half}) std::remove(f.c_str());
}

// An interrupted part is written with the units it has: merge refuses it
// as unfinished, naming it, and --preview takes it.
TEST(PartsMerge, AnInterruptedPartIsUnfinished) {
  auto scene = load_scene(std::string(LANTERN_SOURCE_DIR) + "/scenes/cornell-box.pbrt");
  RenderOptions o = parts_render("path");
  const std::string p1 = render_part(*scene, o, 0, 2);
  std::atomic<bool> cancel{true};  // stops after the waves in flight
  RenderHooks hooks;
  hooks.cancel = &cancel;
  const std::string p2 = render_part(*scene, o, 1, 2, "", hooks);
  try {
    merge_parts({p1, p2}, false);
    ADD_FAILURE() << "an unfinished part was merged";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("part 2/2 (" + p2 + ") is unfinished"), std::string::npos) << e.what();
  }
  EXPECT_FALSE(merge_parts({p1, p2}, true).complete);
  std::remove(p1.c_str());
  std::remove(p2.c_str());
}

}  // namespace
}  // namespace lantern
