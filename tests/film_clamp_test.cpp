// pbrt-v4's Film "maxcomponentvalue": samples whose largest component in
// the sensor's RGB (for the default "cie1931" sensor: CIE XYZ times the
// imaging ratio, exposure time * iso / 100) exceeds the value are scaled
// down to it. Checked against the closed form on an emitter that fills the
// view, where every sample carries the same radiance.
#include <gtest/gtest.h>

#include "expect_error.h"
#include "lantern/render.h"
#include "lantern/scene.h"

namespace lantern {
namespace {

std::string emitter_text(const std::string& film_params) {
  return R"(
Film "rgb" "integer xresolution" [ 8 ] "integer yresolution" [ 8 ] )" + film_params + R"(
Camera "perspective" "float fov" [ 30 ]
WorldBegin
AttributeBegin
  AreaLightSource "diffuse" "rgb L" [ 4 2 1 ]
  Shape "trianglemesh" "point3 P" [ -10 -10 5  10 -10 5  10 10 5  -10 10 5 ] "integer indices" [ 0 2 1 0 3 2 ]
AttributeEnd
)";
}

std::shared_ptr<Scene> emitter_scene(const std::string& film_params) {
  return load_scene_from_string(emitter_text(film_params), "clamp.pbrt");
}

Image render_emitter(const std::string& film_params) {
  RenderOptions o;
  o.spp = 4;
  o.maxdepth = 1;
  return render(*emitter_scene(film_params), o).image;
}

// The pixel's value against the expected colour, relative.
void expect_pixels(const Image& img, float r, float g, float b) {
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x) {
      EXPECT_NEAR(img.at(x, y)[0], r, 1e-3f * r);
      EXPECT_NEAR(img.at(x, y)[1], g, 1e-3f * g);
      EXPECT_NEAR(img.at(x, y)[2], b, 1e-3f * b);
    }
}

TEST(FilmClamp, ScalesSamplesWhoseLargestXyzComponentIsAboveTheValue) {
  expect_pixels(render_emitter(""), 4.f, 2.f, 1.f);
  // Linear sRGB (4, 2, 1) in XYZ (IEC 61966-2-1's matrix): X = 2.5453,
  // Y = 2.3530, Z = 1.2661. The largest, X, is brought to 1.5.
  const float s = 1.5f / (0.4124f * 4.f + 0.3576f * 2.f + 0.1805f * 1.f);
  expect_pixels(render_emitter(R"("float maxcomponentvalue" [ 1.5 ])"), 4.f * s, 2.f * s, 1.f * s);
  // Above the largest component: nothing changes.
  expect_pixels(render_emitter(R"("float maxcomponentvalue" [ 3 ])"), 4.f, 2.f, 1.f);
  // The imaging ratio (iso 200: twice) enters the sensor's RGB before the
  // clamp, and the image after it.
  expect_pixels(render_emitter(R"("float maxcomponentvalue" [ 1.5 ] "float iso" [ 200 ])"), 8.f * s / 2.f,
                4.f * s / 2.f, 2.f * s / 2.f);
}

TEST(FilmClamp, RefusesValuesThatAreNotPositive) {
  expect_load_error(emitter_text(R"("float maxcomponentvalue" [ 0 ])"), "clamp.pbrt",
                    {"clamp.pbrt:2", "\"maxcomponentvalue\" must be a number > 0"});
}

}  // namespace
}  // namespace lantern
