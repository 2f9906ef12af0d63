// pbrt-v4's Film "gbuffer": the first visible surface's channels and the
// samples' variance, against closed forms of a square seen head-on and
// against the spread of independent renders.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <map>

#include "expect_error.h"
#include "lantern/image.h"
#include "lantern/render.h"
#include "lantern/scene.h"
#include "stop_and_resume.h"

namespace lantern {
namespace {

// A square of side 2 in the plane z = 0, seen head-on from 5 away with a
// 30-degree view: it fills the image's middle. pbrt's LookAt puts camera
// space's z along the view and its x along up x view, which is the
// world's -x here.
std::string square_scene(const std::string& film_extra) {
  return R"(
LookAt 0 0 5  0 0 0  0 1 0
Camera "perspective" "float fov" 30
Film "gbuffer" "integer xresolution" 32 "integer yresolution" 24 "string filename" "gb.exr" )" +
         film_extra + R"(
Sampler "independent" "integer pixelsamples" 16
WorldBegin
LightSource "infinite" "rgb L" [1 1 1]
Material "diffuse" "rgb reflectance" [0.7 0.4 0.2]
Shape "trianglemesh" "point3 P" [-1 -1 0  1 -1 0  1 1 0  -1 1 0] "integer indices" [0 1 2 0 2 3]
  "point2 uv" [0 0 1 0 1 1 0 1]
)";
}

std::map<std::string, float> channels_at(const Image& img, int x, int y) {
  std::map<std::string, float> m;
  const size_t n = img.channel_names.size(), i = size_t(y) * size_t(img.width) + size_t(x);
  for (size_t c = 0; c < n; ++c) m[img.channel_names[c]] = img.channels[i * n + c];
  return m;
}

RenderResult render_gbuffer(const Scene& scene, const char* integrator = "path", uint64_t seed = 0) {
  RenderOptions o;
  o.sampler = scene_settings(scene).sampler;
  o.sampler.seed = int(seed);
  o.integrator = parse_integrator(integrator);
  o.spp = 16;
  o.seed = seed;
  o.maxdepth = 5;
  o.gbuffer = scene_settings(scene).gbuffer;
  o.gbuffer_world = scene_settings(scene).gbuffer_world;
  return render(scene, o);
}

TEST(GBuffer, ChannelsOfASquareSeenHeadOn) {
  auto scene = load_scene_from_string(square_scene(""), "gb.pbrt", {});
  ASSERT_TRUE(scene_settings(*scene).gbuffer);
  const Image img = render_gbuffer(*scene).image;
  ASSERT_EQ(img.channel_names.size(), 22u);
  EXPECT_EQ(img.channel_names[0], "Albedo.R");
  EXPECT_EQ(img.channel_names.back(), "RelativeVariance.B");
  auto c = channels_at(img, 16, 12);  // the middle: all square
  EXPECT_NEAR(c["Albedo.R"], 0.7f, 1e-5f);
  EXPECT_NEAR(c["Albedo.G"], 0.4f, 1e-5f);
  EXPECT_NEAR(c["Albedo.B"], 0.2f, 1e-5f);
  EXPECT_NEAR(c["P.Z"], 5.f, 1e-4f);  // every point of the square lies 5 along the view
  EXPECT_NEAR(c["N.X"], 0.f, 1e-6f);
  EXPECT_NEAR(c["N.Z"], -1.f, 1e-6f);  // the square's normal (+z) faces the camera: -z in camera space
  EXPECT_NEAR(c["Ns.Z"], -1.f, 1e-6f);
  EXPECT_NEAR(c["dzdx"], 0.f, 1e-5f);
  EXPECT_NEAR(c["u"], 0.5f, 0.03f);
  EXPECT_NEAR(c["v"], 0.5f, 0.03f);
  // Left and right of the middle, mirrored; the image's right is camera
  // space's +x, the world's -x (pbrt's convention, as its images show).
  auto right = channels_at(img, 22, 12), left = channels_at(img, 9, 12);
  EXPECT_GT(right["P.X"], 0.1f);
  EXPECT_NEAR(right["P.X"], -left["P.X"], 0.03f);  // each the mean of 16 points over a pixel 0.11 wide
  EXPECT_LT(right["u"], 0.5f);                     // u follows world x
  // The corner sees the sky: no surface, nothing but the variance (0).
  auto corner = channels_at(img, 0, 0);
  for (const char* k : {"Albedo.R", "P.Z", "N.Z", "u", "Variance.R"}) EXPECT_EQ(corner[k], 0.f) << k;

  // In world coordinates: the square's plane and normal themselves.
  auto world = load_scene_from_string(square_scene("\"string coordinatesystem\" \"world\""), "gb.pbrt", {});
  const Image w = render_gbuffer(*world).image;
  auto m = channels_at(w, 22, 12);
  EXPECT_NEAR(m["P.Z"], 0.f, 1e-5f);
  EXPECT_NEAR(m["P.X"], -right["P.X"], 1e-4f);
  EXPECT_NEAR(m["N.Z"], 1.f, 1e-6f);

  // Wound the other way, its normals point away from the camera; pbrt-v4
  // turns them to face it (measured with pbrt-v4 on a floor wound
  // downwards: N in camera space (0, 0.985, -0.172), up towards a camera
  // above it), and so does Lantern.
  std::string reversed = square_scene("");
  const std::string order = "[0 1 2 0 2 3]";
  reversed.replace(reversed.find(order), order.size(), "[0 2 1 0 3 2]");
  auto flipped = load_scene_from_string(reversed, "gb.pbrt", {});
  auto f = channels_at(render_gbuffer(*flipped).image, 16, 12);
  EXPECT_NEAR(f["N.Z"], -1.f, 1e-6f);
  EXPECT_NEAR(f["Ns.Z"], -1.f, 1e-6f);
  expect_load_error("Film \"gbuffer\" \"string coordinatesystem\" \"screen\"\n", "c.pbrt",
                    {"c.pbrt:1", "\"screen\"", "\"camera\" or \"world\""});
}

// The depth slope of a tilted square: the camera-space z of dp/dx as
// pbrt-v4 approximates it, from its camera's smallest direction
// differential over the film (at a corner) and scaled for the samples per
// pixel (max(1/8, 1/sqrt(spp)) = 1/4 at the Film's 16).
TEST(GBuffer, DepthSlopesFollowATiltedSquare) {
  std::string text = square_scene("");
  text.replace(text.find("Material"), 0, "Rotate 40 0 1 0\n");
  auto scene = load_scene_from_string(text, "tilt.pbrt", {});
  auto c = channels_at(render_gbuffer(*scene).image, 16, 12);
  // Along the view's axis the depth of the plane at 40 degrees changes by
  // 5 tan(40) per unit of a = tan(angle); a pixel is 2 tan(15) / 24 of a.
  // The unit direction's derivative is smallest at the film's corner
  // (a, b) = (tan 15 * 32 / 24, tan 15): (1 + b^2) / (1 + a^2 + b^2)^1.5.
  const float t = std::tan(glm::radians(15.f)), a = t * 32.f / 24.f, b = t;
  const float corner = (1.f + b * b) / std::pow(1.f + a * a + b * b, 1.5f);
  const float expected = 0.25f * 5.f * std::tan(glm::radians(40.f)) * (2.f * t / 24.f) * corner;
  EXPECT_NEAR(c["dzdx"], expected, 0.05f * expected);
  EXPECT_LT(c["dzdy"], 0.1f * expected);  // half a pixel off the axis: nearly flat
}

// Under a filter with negative lobes each sample counts with the
// filter's sign, as pbrt-v4's GBufferFilm weighs its samples: the albedo
// is the signed sum over the signed count. An orthographic camera sees a
// square whose vertical edges lie on pixel boundaries (x = 7 and 25 of
// 32), so the pixels beside it (centres half a pixel outside) see the
// square with the share of the filter's integral beyond half a pixel.
// For pbrt-v4's sinc (radius 4, tau 3) that share is 0.0746 signed and
// 0.1856 of the filter's magnitude (integrated numerically); the albedo
// there is 0.7 times it.
TEST(GBuffer, SignedFiltersWeighTheirSamplesBySign) {
  const std::string text = R"(
LookAt 0 0 5  0 0 0  0 1 0
Camera "orthographic"
Film "gbuffer" "integer xresolution" 32 "integer yresolution" 24 "string filename" "gb.exr"
PixelFilter "sinc"
Sampler "independent" "integer pixelsamples" 64
WorldBegin
Material "diffuse" "rgb reflectance" [0.7 0.4 0.2]
Shape "trianglemesh" "point3 P" [-0.75 -3 0  0.75 -3 0  0.75 3 0  -0.75 3 0] "integer indices" [0 1 2 0 2 3]
)";
  auto scene = load_scene_from_string(text, "signed.pbrt", {});
  RenderOptions o;
  o.sampler = scene_settings(*scene).sampler;
  o.spp = 64;
  o.maxdepth = 1;
  o.gbuffer = true;
  const Image img = render(*scene, o).image;
  double beside = 0.0;
  for (int y = 0; y < 24; ++y) beside += channels_at(img, 6, y)["Albedo.R"] + channels_at(img, 25, y)["Albedo.R"];
  beside /= 48.0;
  EXPECT_NEAR(beside, 0.7 * 0.0746, 0.02) << "unsigned, it would be " << 0.7 * 0.1856;
  // Inside, every sample that lands on the square sees the same point's
  // depth, whatever their signs.
  EXPECT_NEAR(channels_at(img, 16, 12)["P.Z"], 5.f, 1e-4f);
  EXPECT_NEAR(channels_at(img, 16, 12)["Albedo.R"], 0.7f, 0.02f);
}

// The variance is the samples' own: over independent renders, a pixel's
// value spreads by its samples' variance over their count.
TEST(GBuffer, VarianceIsTheSamplesVariance) {
  std::string text = square_scene("");
  // A small light makes the samples noisy.
  text.replace(text.find("LightSource"), std::string("LightSource \"infinite\" \"rgb L\" [1 1 1]").size(),
               "AttributeBegin\nAreaLightSource \"diffuse\" \"rgb L\" [3 3 3]\nTranslate 0.5 0.5 1.5\n"
               "Shape \"sphere\" \"float radius\" 0.5\nAttributeEnd");
  auto scene = load_scene_from_string(text, "var.pbrt", {});
  constexpr int kRuns = 24;
  std::vector<Image> runs;
  for (int r = 0; r < kRuns; ++r) runs.push_back(render_gbuffer(*scene, "path", uint64_t(r + 1)).image);
  double spread = 0.0, reported = 0.0;
  int pixels = 0;
  for (int y = 7; y < 17; ++y)
    for (int x = 10; x < 22; ++x) {
      double mean = 0.0, var = 0.0;
      for (const Image& im : runs) mean += im.at(x, y)[1] / kRuns;
      for (const Image& im : runs) var += (im.at(x, y)[1] - mean) * (im.at(x, y)[1] - mean) / (kRuns - 1);
      spread += var;
      for (const Image& im : runs) reported += channels_at(im, x, y)["Variance.G"] / 16.0 / kRuns;
      ++pixels;
    }
  // 120 pixels of 11 degrees of freedom each: the ratio within 15%.
  EXPECT_NEAR(spread / reported, 1.0, 0.15) << spread / pixels << " against " << reported / pixels;
}

// A render stopped and resumed gives every channel, the variance
// included, bit for bit as the render that ran through (the squares'
// sums are in the checkpoint), on 1 and 2 threads.
TEST(GBuffer, ResumedRendersKeepEveryChannel) {
  auto scene = load_scene_from_string(square_scene(""), "gb.pbrt", {});
  RenderOptions o;
  o.spp = 16;
  o.wave_size = 256;
  o.gbuffer = true;
  o.threads = 2;
  const Image straight = render(*scene, o).image;
  const auto dir = std::filesystem::temp_directory_path() / ("lantern-gbuffer-" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  int runs = 0;
  const Image resumed = render_stopped_and_resumed(*scene, o, (dir / "gb.ckpt").string(), 2, 3, &runs).image;
  EXPECT_GT(runs, 1);
  EXPECT_EQ(resumed.rgb, straight.rgb);
  EXPECT_EQ(resumed.channels, straight.channels);
}

// Every integrator gets the channels (lt, which takes no camera samples,
// from the budget's count); the file keeps them; shares are refused.
TEST(GBuffer, EveryIntegratorAndTheFile) {
  auto scene = load_scene_from_string(square_scene(""), "gb.pbrt", {});
  const Image path = render_gbuffer(*scene, "path").image;
  for (const char* integrator : {"bdpt", "lt", "vcm"}) {
    const Image other = render_gbuffer(*scene, integrator).image;
    ASSERT_EQ(other.channel_names, path.channel_names) << integrator;
    auto a = channels_at(path, 16, 12), b = channels_at(other, 16, 12);
    for (const char* k : {"Albedo.R", "P.Z", "N.Z", "u", "v"}) EXPECT_EQ(a[k], b[k]) << integrator << " " << k;
  }
  const auto dir = std::filesystem::temp_directory_path() / ("lantern-gbuffer-" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  write_image((dir / "gb.exr").string(), path, {});
  const Image back = read_image((dir / "gb.exr").string());
  ASSERT_EQ(back.channel_names.size(), path.channel_names.size());
  for (int y : {0, 12})
    for (int x : {0, 16}) {
      auto a = channels_at(path, x, y), b = channels_at(back, x, y);
      EXPECT_EQ(a, b) << x << "," << y;
    }
  RenderOptions o;
  o.gbuffer = true;
  o.share_count = 2;
  o.film_path = (dir / "part").string();
  EXPECT_THROW(render(*scene, o), std::invalid_argument);
}

}  // namespace
}  // namespace lantern
