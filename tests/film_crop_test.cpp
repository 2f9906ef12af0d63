// Film "cropwindow" and "pixelbounds": the film holds part of the camera's
// image, and that part is the whole image's there, for camera samples and
// for light-tracing splats (normalised over the whole image: pbrt-v4
// itself normalises them over the crop, so its bdpt and lightpath are off
// on crops, and they are held here to Lantern's own uncropped image).
#include <gtest/gtest.h>

#include <fstream>
#include <stdexcept>

#include "expect_error.h"
#include "film/film.h"
#include "integrator/render_settings.h"
#include "lantern/render.h"
#include "lantern/scene.h"
#include "stat_compare.h"

namespace lantern {
namespace {

std::string scene_with(const std::string& film_extra) {
  return "LookAt 0 1 3.5  0 1 0  0 1 0\nCamera \"perspective\" \"float fov\" 40\n"
         "Film \"rgb\" \"integer xresolution\" 32 \"integer yresolution\" 24 " + film_extra + "\n"
         "WorldBegin\nLightSource \"infinite\" \"rgb L\" [0.3 0.35 0.4]\n"
         "AttributeBegin\n AreaLightSource \"diffuse\" \"rgb L\" [8 7 6]\n Translate 0 1.9 0\n"
         " Shape \"disk\" \"float radius\" 0.3\nAttributeEnd\n"
         "Material \"diffuse\" \"rgb reflectance\" [0.7 0.3 0.2]\nShape \"sphere\" \"float radius\" 0.5\n"
         "Material \"diffuse\" \"rgb reflectance\" [0.5 0.5 0.5]\n"
         "Shape \"trianglemesh\" \"point3 P\" [-3 -0.5 -3  3 -0.5 -3  3 -0.5 3  -3 -0.5 3] \"integer indices\" [0 1 2 0 2 3]\n";
}

RegionStats stats(const Scene& scene, const std::string& integrator, const std::vector<Region>& regions) {
  RenderOptions o;
  o.integrator = parse_integrator(integrator);
  o.spp = integrator == "lt" ? 256 : 64;
  o.maxdepth = 5;
  return stats_of(render_runs(scene, o, 6, 11), regions);
}

// The crop x 0.25-0.75, y 0.5-1 of 32x24 is pixels 8-24 by 12-24: its
// regions against the same pixels of the whole image.
TEST(FilmCrop, TheCropIsTheWholeImagesPart) {
  auto whole = load_scene_from_string(scene_with(""), "whole.pbrt", {});
  auto crop = load_scene_from_string(scene_with("\"float cropwindow\" [0.25 0.75 0.5 1]"), "crop.pbrt", {});
  const RenderResult r = render(*crop, RenderOptions{.spp = 1});
  ASSERT_EQ(r.image.width, 16);
  ASSERT_EQ(r.image.height, 12);
  const std::vector<Region> in_crop = {{0, 0, 8, 6}, {8, 0, 8, 6}, {0, 6, 8, 6}, {8, 6, 8, 6}};
  std::vector<Region> in_whole = in_crop;
  for (Region& g : in_whole) g.x0 += 8, g.y0 += 12;
  for (const char* integrator : {"path", "bdpt", "lt"}) {
    const RegionStats a = stats(*crop, integrator, in_crop), b = stats(*whole, integrator, in_whole);
    expect_means_agree(a, b, 0.01, integrator);
  }
}

// A crop window's pixels are pbrt-v4's, whose products of resolution and
// window are floats: 480 x 270 cropped to x 0.1-0.45, y 0.65-1 is pixels
// 48-216 by 176-270 in pbrt-v4 (its image 168 x 94, measured); in doubles
// 480 * 0.1f is 48.0000007, and the crop began a pixel later.
TEST(FilmCrop, TheCropsPixelsArePbrtV4s) {
  auto scene = load_scene_from_string(scene_with(""), "whole.pbrt", {});
  RenderOptions o;
  o.width = 480;
  o.height = 270;
  o.crop_window = {0.1f, 0.45f, 0.65f, 1.f};
  const ImageRegion r = image_region(*scene, o);
  EXPECT_EQ(r.x0, 48);
  EXPECT_EQ(r.width, 168);
  EXPECT_EQ(r.y0, 176);
  EXPECT_EQ(r.height, 94);
}

// Adaptive sampling's view of a cropped pixel (Film::halves) is what the
// image shows: splats normalised over the whole image there too.
TEST(FilmCrop, HalvesOfACroppedPixelAreItsValue) {
  PixelFilter box;
  box.type = PixelFilter::Type::Box;
  box.radius = Vec2(0.5f);
  Film film(4, 4, box);
  film.set_region(2, 2, 8, 8);
  film.track_halves();
  WaveOutput out;
  for (uint32_t k = 0; k < 4; ++k) out.samples.push_back({5, RGB(0.25f * float(k + 1)), (k & 1) != 0});
  out.splats.push_back({Vec2(3.5f, 3.5f), RGB(2.f), false});  // the film's pixel (1, 1) = 5
  out.splats.push_back({Vec2(3.5f, 3.5f), RGB(1.f), true});
  out.light_paths = 4;
  out.odd_light_paths = 2;
  film.prepare(out);
  film.merge(out);
  const Image img = film.resolve();
  for (int c = 0; c < 3; ++c) {
    const Film::Halves h = film.halves(5, c);
    EXPECT_NEAR(h.value, double(img.rgb[3 * 5 + size_t(c)]), 1e-6);
    EXPECT_NEAR(0.5 * (h.even + h.odd), h.value, 1e-6);  // equal halves: their mean is the pixel
  }
}

TEST(FilmCrop, PixelBoundsAndTheirErrors) {
  auto bounded = load_scene_from_string(scene_with("\"integer pixelbounds\" [3 10 20 24]"), "b.pbrt", {});
  const RenderResult r = render(*bounded, RenderOptions{.spp = 1});
  EXPECT_EQ(r.image.width, 7);
  EXPECT_EQ(r.image.height, 4);
  expect_load_error(scene_with("\"float cropwindow\" [0 1 0 1] \"integer pixelbounds\" [0 4 0 4]"), "both.pbrt",
                    {"both.pbrt:3", "not both"});
  expect_load_error(scene_with("\"integer pixelbounds\" [4 2 0 4]"), "pb.pbrt", {"pb.pbrt:3", "x0 < x1"});
  expect_load_error(scene_with("\"float cropwindow\" [0 1 0]"), "cw.pbrt", {"cw.pbrt:3", "four values"});
  auto empty = load_scene_from_string(scene_with("\"float cropwindow\" [0.5 0.5 0 1]"), "e.pbrt", {});
  EXPECT_THROW(render(*empty, RenderOptions{.spp = 1}), std::invalid_argument);
}

// A film larger than the machine's memory is refused before it is
// allocated, saying what it needs and what to do; a crop of the same image
// needs only its own pixels.
TEST(FilmCrop, AFilmTooLargeForMemoryIsRefusedWithWhatItNeeds) {
  {
    std::ifstream meminfo("/proc/meminfo");
    std::string key;
    double kb = 0.0;
    while (meminfo >> key >> kb && key != "MemAvailable:") meminfo.ignore(256, '\n');
    if (kb > 300.0 * 1024 * 1024) GTEST_SKIP() << "this machine has room for a 256 GiB film";
  }
  auto scene = load_scene_from_string(scene_with(""), "big.pbrt", {});
  RenderOptions o{.spp = 1};
  o.width = o.height = 65536;  // 4.3 billion pixels: about 256 GiB
  try {
    render(*scene, o);
    ADD_FAILURE() << "a 65536x65536 film was not refused";
  } catch (const std::invalid_argument& e) {
    const std::string msg = e.what();
    for (const char* f : {"65536x65536 film needs about 256.0 GiB", "available", "cropwindow"})
      EXPECT_NE(msg.find(f), std::string::npos) << msg;
  }
  auto cropped = load_scene_from_string(scene_with("\"integer pixelbounds\" [0 8 0 8]"), "crop.pbrt", {});
  EXPECT_EQ(render(*cropped, o).image.width, 8);
  // Per-strategy images count too: at maxdepth 100, 5250 strategies of 72
  // bytes a pixel make a 4096x4096 film about 5.8 TiB (where without them
  // it is 1.75 GiB, and renders).
  RenderOptions s{.integrator = Integrator::Bdpt, .spp = 1, .maxdepth = 100};
  s.width = s.height = 4096;
  s.strategies = true;
  try {
    render(*scene, s);
    ADD_FAILURE() << "per-strategy images of 5.8 TiB were not refused";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("--strategies"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace lantern
