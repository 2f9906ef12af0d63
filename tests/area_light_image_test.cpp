// Area lights scaled by an image (pbrt-v4's "filename" on diffuse area
// lights): a uniform image of 1 is the plain light; a coloured
// image is rendered alike by path tracing, bdpt and light tracing, the light
// seen directly included; "L" with "filename" is an error.
#include <gtest/gtest.h>

#include <filesystem>

#include "expect_error.h"
#include "stat_compare.h"

namespace lantern {
namespace {

std::string image_file(const char* name, std::vector<float> rgb, int w, int h) {
  auto dir = std::filesystem::temp_directory_path() / ("lantern-light-image-test-" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  std::string path = (dir / name).string();
  write_image(path, Image{w, h, std::move(rgb)}, {});
  return path;
}

std::string scene_text(const std::string& light_params) {
  return R"(
LookAt 0 1.2 -3  0 0.8 0  0 1 0
Camera "perspective" "float fov" [ 50 ]
Film "rgb" "integer xresolution" [ 24 ] "integer yresolution" [ 16 ]
WorldBegin
AttributeBegin
  AreaLightSource "diffuse" )" + light_params + R"(
  Shape "bilinearmesh" "point3 P" [ -0.6 0.6 1  0.6 0.6 1  -0.6 1.8 1  0.6 1.8 1 ]
AttributeEnd
Material "diffuse" "rgb reflectance" [ 0.6 0.6 0.6 ]
Shape "trianglemesh" "point3 P" [ -3 0 -3  3 0 -3  3 0 3  -3 0 3 ] "integer indices" [ 0 2 1  0 3 2 ]
Shape "sphere" "float radius" [ 0.3 ]
)";
}

TEST(AreaLightImage, UniformImageIsThePlainLight) {
  std::string ones = image_file("ones.exr", std::vector<float>(12, 1.f), 2, 2);
  auto plain = load_scene_from_string(scene_text(R"("rgb L" [ 3 3 3 ])"), "plain.pbrt");
  auto imaged = load_scene_from_string(scene_text(R"("float scale" [ 3 ] "string filename" ")" + ones + "\""),
                                       "imaged.pbrt");
  RenderOptions o;
  o.spp = 4;
  for (const char* integrator : {"path", "bdpt", "lt"}) {
    o.integrator = parse_integrator(integrator);
    // The same paths: bilinear weights of an all-ones image sum to 1 up to rounding.
    Image a = render(*plain, o).image, b = render(*imaged, o).image;
    for (size_t k = 0; k < a.rgb.size(); ++k) ASSERT_NEAR(a.rgb[k], b.rgb[k], 1e-5f * (1.f + a.rgb[k])) << integrator;
  }
}

TEST(AreaLightImage, PathBdptAndLightTracingAgree) {
  std::string img = image_file("colours.exr", {4, 0, 0, 0, 4, 0, 0, 0, 4, 1, 1, 1}, 2, 2);
  auto scene = load_scene_from_string(scene_text(R"("string filename" ")" + img + "\""), "colours.pbrt");
  const std::vector<Region> regions = {{0, 0, 24, 16}, {4, 0, 8, 6}, {12, 0, 8, 6}, {0, 10, 12, 6}, {12, 10, 12, 6}};
  auto path = render_stats(*scene, "path", 24, 16, 64, 10, regions);
  auto bdpt = render_stats(*scene, "bdpt", 24, 16, 16, 10, regions);
  auto lt = render_stats(*scene, "lt", 24, 16, 32, 10, regions);
  EXPECT_LT(max_z(bdpt, path), 4.5);
  EXPECT_LT(max_z(lt, path), 4.5);
}

TEST(AreaLightImage, LWithFilenameIsAnError) {
  std::string ones = image_file("ones2.exr", std::vector<float>(12, 1.f), 2, 2);
  expect_load_error(scene_text(R"("rgb L" [ 1 1 1 ] "string filename" ")" + ones + "\""), "both.pbrt",
                    {"both.pbrt:7", "either \"L\" or \"filename\""});
}

// "power", as pbrt-v4 reads it: every primitive is a light of its own that
// emits the whole power (pbrt-v4 makes one light per triangle), over its
// own area, both sides when two-sided, and an image's mean luminance
// (measured in pbrt-v4: a two-sided two-triangle quad of power 20 is twice
// as bright as the quad's area alone would make it, tests/conformance).
TEST(AreaLightImage, PowerIsPerPrimitiveAsInPbrtV4) {
  // Two triangles of areas 0.5 and 1 (a right triangle split unevenly).
  const std::string mesh = R"(
  Shape "trianglemesh" "point3 P" [ 0 0 0  1 0 0  1 1 0  -1 1 0 ] "integer indices" [ 0 1 2  0 2 3 ] "point2 uv" [ 0 0 1 0 1 1 0 1 ]
AttributeEnd
)";
  auto lights = [&](const std::string& params) {
    auto s = load_scene_from_string("WorldBegin\nAttributeBegin\n  AreaLightSource \"diffuse\" " + params + mesh, "p.pbrt", {});
    return s->lights.area;
  };
  auto a = lights(R"("rgb L" [ 1 0.5 0.25 ] "float power" [ 10 ] "bool twosided" true)");
  ASSERT_EQ(a.size(), 2u);
  EXPECT_NEAR(a[0].L[0], 10.f / (2.f * 0.5f * kPi), 1e-4f);
  EXPECT_NEAR(a[1].L[0], 10.f / (2.f * 1.0f * kPi), 1e-4f);
  EXPECT_NEAR(a[1].L[2], 0.25f * 10.f / (2.f * kPi), 1e-4f) << "the colour is kept";
  // An image: normalised by its mean luminance (Y of sRGB), not its mean.
  const std::string orange = image_file("orange.exr", {0.8f, 0.4f, 0.1f, 0.8f, 0.4f, 0.1f, 0.8f, 0.4f, 0.1f, 0.8f, 0.4f, 0.1f}, 2, 2);
  auto b = lights("\"string filename\" \"" + orange + "\" \"float power\" [ 10 ]");
  const float y = 0.2126f * 0.8f + 0.7152f * 0.4f + 0.0722f * 0.1f;
  EXPECT_NEAR(b[1].L[0], 10.f / (kPi * y), 1e-3f);
}

}  // namespace
}  // namespace lantern
