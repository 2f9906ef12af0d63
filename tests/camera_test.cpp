// Orthographic and spherical cameras: images of known scenes against closed
// forms (a constant environment gives a constant image; a square's
// footprint under parallel projection), film positions that round-trip
// through the importance functions light tracing uses, and path, bdpt and
// lt agreeing with each camera that light subpaths can reach.
#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>

#include "camera/camera.h"
#include "expect_error.h"
#include "math/rng.h"
#include "sanitizer.h"
#include "stat_compare.h"

namespace lantern {
namespace {

double camera_image_mean(const Image& im, int channel) {
  double s = 0.0;
  for (int y = 0; y < im.height; ++y)
    for (int x = 0; x < im.width; ++x) s += im.at(x, y)[channel];
  return s / (double(im.width) * im.height);
}

TEST(Camera, SphericalCameraSeesAConstantEnvironmentAsAConstantImage) {
  for (const char* mapping : {"equalarea", "equirectangular"}) {
    auto scene = load_scene_from_string(std::string(R"(
LookAt 1 2 3  0 0 0  0 1 0
Camera "spherical" "string mapping" ")") + mapping + R"("
Film "rgb" "integer xresolution" [ 32 ] "integer yresolution" [ 16 ]
WorldBegin
LightSource "infinite" "rgb L" [ 0.3 0.6 0.9 ]
)",
                                        "env.pbrt");
    RenderOptions o;
    o.spp = 2;
    Image im = render(*scene, o).image;
    for (int y = 0; y < im.height; ++y)
      for (int x = 0; x < im.width; ++x) ASSERT_NEAR(im.at(x, y)[1], 0.6f, 1e-5f) << mapping << " " << x << "," << y;
  }
}

// Parallel projection of a unit square emitter onto a 4 x 2 screen window:
// it covers an eighth of the film, wherever it sits in depth.
TEST(Camera, OrthographicFootprintOfASquareIsItsArea) {
  for (const char* depth : {"2", "50"}) {
    auto scene = load_scene_from_string(std::string(R"(
LookAt 0 0 -10  0 0 0  0 1 0
Camera "orthographic" "float screenwindow" [ -2 2 -1 1 ]
Film "rgb" "integer xresolution" [ 64 ] "integer yresolution" [ 32 ]
Sampler "stratified" "integer xsamples" [ 4 ] "integer ysamples" [ 4 ]
WorldBegin
AttributeBegin
  AreaLightSource "diffuse" "rgb L" [ 2 2 2 ]
  Translate 0.3 -0.2 )") + depth + R"(
  Shape "trianglemesh" "point3 P" [ -0.5 -0.5 0  0.5 -0.5 0  0.5 0.5 0  -0.5 0.5 0 ] "integer indices" [ 0 2 1 0 3 2 ]
AttributeEnd
)",
                                        "ortho.pbrt");
    RenderOptions o;
    o.spp = 16;
    EXPECT_NEAR(camera_image_mean(render(*scene, o).image, 0), 2.0 / 8.0, 2e-3) << "depth " << depth;
  }
}

// The film position of a camera ray's direction, as light tracing finds it
// from the importance function, is the position the ray was made for.
TEST(Camera, ImportanceFindsTheFilmPositionOfEachRay) {
  for (bool equal_area : {true, false}) {
    CameraDesc d;
    d.projection = Projection::Spherical;
    d.equal_area = equal_area;
    d.world_from_camera = glm::rotate(glm::translate(Mat4(1.f), Vec3(1, 2, 3)), 0.6f, glm::normalize(Vec3(1, 1, 0)));
    Camera cam(d, 64, 32);
    RandomStream rng = RandomStream::make(1, 0, 0);
    for (int i = 0; i < 2000; ++i) {
      // The first rays look just off the poles, where precision is scarcest.
      Vec2 p(rng.get1d() * 64.f, i == 0 ? 1e-4f : i == 1 ? 32.f - 1e-4f : rng.get1d() * 32.f);
      CameraRay r = cam.generate_ray(p, Vec2(0.5f));
      Vec2 back;
      float We = cam.We(r.o, r.d, &back);
      ASSERT_GT(We, 0.f);
      EXPECT_FLOAT_EQ(We, cam.pdf_dir(r.d));
      EXPECT_NEAR(back.y, p.y, 2e-2f) << equal_area;
      if (i < 2) continue;  // at a pole, x (the azimuth) is undetermined
      // Equal-area positions are exact up to rounding; across the
      // equirectangular seam x wraps.
      float dx = std::fabs(back.x - p.x);
      dx = std::fmin(dx, 64.f - dx);
      EXPECT_LT(dx, 2e-2f) << equal_area;
    }
    // The importance integrates to 1 over the sphere (a point sensor).
    double sum = 0.0;
    const int n = 200000;
    for (int i = 0; i < n; ++i) {
      float z = 1.f - 2.f * rng.get1d(), phi = 2.f * kPi * rng.get1d(), s = safe_sqrt(1.f - z * z);
      Vec3 w(s * std::cos(phi), s * std::sin(phi), z);
      Vec2 back;
      sum += cam.We(Vec3(1, 2, 3), w, &back) * 4.0 * kPi;
    }
    EXPECT_NEAR(sum / n, 1.0, equal_area ? 1e-6 : 2e-2) << equal_area;
  }
}

// A thin-lens orthographic camera: the importance finds each ray's film
// point, and a lens point chosen to see a scene point (sample_wi) is the
// ray the camera itself generates from the raster point it reports, with
// the same lens sample; importance over the two densities is the
// perspective camera's 1 / cos.
TEST(Camera, OrthographicLensImportanceFindsItsRays) {
  CameraDesc d;
  d.projection = Projection::Orthographic;
  d.lens_radius = 0.1f;
  d.focal_distance = 2.f;
  d.has_screen_window = true;
  const float window[4] = {-1.5f, 1.5f, -1.f, 1.f};
  std::copy(window, window + 4, d.screen_window);
  d.world_from_camera = glm::rotate(glm::translate(Mat4(1.f), Vec3(1, 2, 3)), 0.6f, glm::normalize(Vec3(1, 1, 0)));
  Camera cam(d, 48, 32);
  RandomStream rng = RandomStream::make(2, 0, 0);
  for (int i = 0; i < 2000; ++i) {
    const Vec2 p(rng.get1d() * 48.f, rng.get1d() * 32.f), u(rng.get1d(), rng.get1d());
    const CameraRay r = cam.generate_ray(p, u);
    Vec2 back;
    const float We = cam.We(r.o, r.d, &back);
    ASSERT_GT(We, 0.f);
    EXPECT_LT(glm::length(back - p), 1e-3f);
    // A point along the ray, seen from the camera with the same lens sample.
    const Vec3 x = r.o + r.d * (0.5f + 4.f * rng.get1d());
    auto cs = cam.sample_wi(x, u);
    ASSERT_TRUE(cs);
    EXPECT_LT(glm::length(cs->p_raster - p), 2e-3f);
    EXPECT_LT(glm::length(cs->p_lens - r.o), 1e-4f);
    EXPECT_LT(glm::length(cs->wi + r.d), 1e-4f);
    EXPECT_NEAR(cs->We / We, 1.f, 1e-3f);
  }
  // The importance integrates to 1 over every origin and direction (cos
  // We dA dw): origins uniform on the film grown by the lens radius,
  // directions uniform in the cone the lens spans.
  const float R = d.lens_radius, cos_max = d.focal_distance / std::sqrt(sqr(d.focal_distance) + sqr(R));
  const double domain = double((3.f + 2.f * R) * (2.f + 2.f * R)) * double(2.f * kPi * (1.f - cos_max));
  const glm::mat3 rot(d.world_from_camera);
  double sum = 0.0;
  const int n = 400000;
  for (int i = 0; i < n; ++i) {
    const Vec3 o(-1.5f - R + (3.f + 2.f * R) * rng.get1d(), -1.f - R + (2.f + 2.f * R) * rng.get1d(), 0.f);
    const Vec3 w = sample_uniform_cone(Vec2(rng.get1d(), rng.get1d()), cos_max);
    Vec2 back;
    sum += double(cam.We(Vec3(d.world_from_camera * Vec4(o, 1.f)), rot * w, &back) * w.z) * domain;
  }
  EXPECT_NEAR(sum / n, 1.0, 0.01);
}

const char* kRoom = R"(
Film "rgb" "integer xresolution" [ 32 ] "integer yresolution" [ 16 ]
WorldBegin
AttributeBegin
  AreaLightSource "diffuse" "rgb L" [ 8 8 8 ]
  Translate 0.5 1.9 0.2 Rotate 90 1 0 0
  Shape "disk" "float radius" [ 0.3 ]
AttributeEnd
Material "diffuse" "rgb reflectance" [ 0.6 0.5 0.4 ]
Shape "trianglemesh" "point3 P" [ -2 0 -2  2 0 -2  2 0 2  -2 0 2  -2 2 -2  2 2 -2  2 2 2  -2 2 2 ]
  "integer indices" [ 0 1 2 0 2 3  4 6 5 4 7 6  0 4 5 0 5 1  1 5 6 1 6 2  2 6 7 2 7 3  3 7 4 3 4 0 ]
AttributeBegin
  Material "diffuse" "rgb reflectance" [ 0.2 0.6 0.3 ]
  Translate -0.6 0.5 0.4
  Shape "sphere" "float radius" [ 0.5 ]
AttributeEnd
)";

// Inside a closed room lit by a small disk: the spherical camera sees every
// wall. Light tracing splats through the spherical importance, and across
// the image's seams (the regions include every edge).
TEST(Camera, IntegratorsAgreeWithASphericalCamera) {
  for (auto [mapping, w, h] : {std::tuple{"equirectangular", 32, 16}, std::tuple{"equalarea", 24, 24}}) {
    // Under the sanitizers one mapping covers the code (the splats across
    // the seams included).
    if (LANTERN_ASAN && std::string(mapping) == "equalarea") continue;
    auto scene = load_scene_from_string(std::string("LookAt 0.2 1 -0.5  0.2 1 1  0 1 0\nCamera \"spherical\" \"string "
                                                    "mapping\" \"") +
                                            mapping + "\"\n" + kRoom,
                                        "spherical.pbrt");
    const int hw = w / 2, hh = h / 2;
    const std::vector<Region> regions = {{0, 0, w, h}, {0, 0, hw, hh}, {hw, 0, hw, hh}, {0, hh, hw, hh}, {hw, hh, hw, hh},
                                         {0, 0, w, 2}, {0, 0, 2, h}};
    auto path = render_stats(*scene, "path", w, h, 32, 16, regions);
    auto bdpt = render_stats(*scene, "bdpt", w, h, 8, 16, regions);
    auto lt = render_stats(*scene, "lt", w, h, 16, 16, regions);
    EXPECT_LT(max_z(bdpt, path), 5.0) << mapping;
    EXPECT_LT(max_z(lt, path), 5.0) << mapping;
  }
}

// Parallel rays: no light path connects to the camera, so bdpt weights its
// remaining strategies without t = 1, and light tracing is refused. With a
// thin lens, light subpaths connect through the lens: bdpt with t = 1 and
// light tracing agree with path tracing.
TEST(Camera, IntegratorsAgreeWithAnOrthographicCamera) {
  for (const char* lens : {"", "\"float lensradius\" [ 0.05 ] \"float focaldistance\" [ 1.5 ]"}) {
    if (LANTERN_ASAN && *lens == '\0') continue;  // the thin lens covers the code under the sanitizers
    auto scene = load_scene_from_string(std::string("LookAt 0.2 1 -1.9  0.2 1 1  0 1 0\nCamera \"orthographic\" ") + lens +
                                            " \"float screenwindow\" [ -1.8 1.8 -0.9 0.9 ]\n" + kRoom,
                                        "ortho-room.pbrt");
    const std::vector<Region> regions = {{0, 0, 32, 16}, {0, 0, 16, 8}, {16, 0, 16, 8}, {0, 8, 16, 8}, {16, 8, 16, 8}};
    auto path = render_stats(*scene, "path", 32, 16, 32, 16, regions);
    auto bdpt = render_stats(*scene, "bdpt", 32, 16, 8, 16, regions);
    EXPECT_LT(max_z(bdpt, path), 5.0) << lens;
    if (*lens != '\0') {
      auto lt = render_stats(*scene, "lt", 32, 16, 32, 16, regions);
      EXPECT_LT(max_z(lt, path), 5.0) << lens;
      continue;
    }
    RenderOptions o;
    o.integrator = Integrator::Lt;
    EXPECT_THROW(render(*scene, o), std::invalid_argument);
  }
}

TEST(Camera, UnsupportedCamerasAreClearErrors) {
  expect_load_error("Camera \"realistic\"\n", "r.pbrt", {"r.pbrt:1", "realistic", "lensfile"});
  expect_load_error("Camera \"spherical\" \"string mapping\" \"cubemap\"\n", "s.pbrt",
                    {"s.pbrt:1", "cubemap", "equirectangular"});
  expect_load_error("Camera \"fisheye\"\n", "f.pbrt", {"f.pbrt:1", "fisheye", "orthographic", "spherical", "realistic"});
}

// The sensor's settings that cannot make an image are errors, as in pbrt-v4
// (the values that can are held against pbrt-v4 by
// tests/conformance/sensor-*.pbrt).
TEST(Camera, SensorSettingsThatMakeNoImageAreClearErrors) {
  expect_load_error("Camera \"perspective\" \"float shutteropen\" 1 \"float shutterclose\" 1\n", "s.pbrt",
                    {"s.pbrt:1", "shutterclose", "never opens"});
  expect_load_error("Film \"rgb\" \"float iso\" 0\n", "i.pbrt", {"i.pbrt:1", "iso", "> 0"});
  expect_load_error("Film \"rgb\" \"float whitebalance\" -5\n", "w.pbrt", {"w.pbrt:1", "whitebalance", "kelvin"});
  expect_load_error("Film \"rgb\" \"string sensor\" \"canon_eos_6d\"\n", "c.pbrt",
                    {"c.pbrt:1", "canon_eos_6d", "cie1931", "canon_eos_5d_mkiv"});
  expect_load_error("ColorSpace \"adobe-rgb\"\n", "a.pbrt", {"a.pbrt:1", "adobe-rgb", "rec2020", "aces2065-1"});
}

// A camera pbrt-v4 names renders with the CIE 1931 observer, balanced from
// 6500 K as pbrt-v4 balances a camera unless the film says otherwise, and
// says so with its line. (pbrt-v4 on a white sky over diffuse patches,
// canon_eos_5d_mkiv against cie1931: grey 0.794 against 0.800, a saturated
// blue (0.1, 0.1, 0.8) read as (0.096, 0.055, 0.741) against (0.100,
// 0.100, 0.801).)
TEST(Camera, NamedCameraSensorsRenderWithTheObserverAndAWarning) {
  for (const char* wb : {"", " \"float whitebalance\" 4000"}) {
    std::vector<std::string> warnings;
    LoadOptions o;
    o.warn = [&](const std::string& w) { warnings.push_back(w); };
    auto s = load_scene_from_string(std::string("Film \"rgb\"\n  \"string sensor\" \"nikon_d850\"") + wb + "\n",
                                    "n.pbrt", o);
    EXPECT_EQ(s->settings.whitebalance, *wb ? 4000.f : 6500.f);
    ASSERT_GE(warnings.size(), 1u);  // (and: the scene has no lights)
    EXPECT_NE(warnings[0].find("n.pbrt:2"), std::string::npos) << warnings[0];
    EXPECT_NE(warnings[0].find("nikon_d850"), std::string::npos) << warnings[0];
    EXPECT_NE(warnings[0].find("CIE 1931"), std::string::npos) << warnings[0];
  }
}

}  // namespace
}  // namespace lantern

namespace lantern {
namespace {

// pbrt-v4's "frameaspectratio": the screen window of a frame of that shape
// (shorter side from -1 to 1), the same image as that window given
// directly, whatever the image's own shape; "screenwindow" wins over it.
TEST(Camera, FrameAspectRatioIsTheScreenWindowOfItsFrame) {
  auto scene = [](const std::string& camera) {
    return load_scene_from_string("LookAt 0 1 -3  0 0.5 0  0 1 0\nCamera " + camera +
                                      "\nFilm \"rgb\" \"integer xresolution\" 24 \"integer yresolution\" 16\n"
                                      "WorldBegin\nLightSource \"infinite\" \"rgb L\" [0.5 0.6 0.7]\n"
                                      "Material \"diffuse\"\nShape \"sphere\" \"float radius\" 0.7\n",
                                  "frame.pbrt");
  };
  for (const char* type : {"\"perspective\" \"float fov\" 40", "\"orthographic\""}) {
    const std::string t = type;
    expect_identical_renders(*scene(t + " \"float frameaspectratio\" 2"),
                             *scene(t + " \"float screenwindow\" [-2 2 -1 1]"), {"path"});
    expect_identical_renders(*scene(t + " \"float frameaspectratio\" 0.5"),
                             *scene(t + " \"float screenwindow\" [-1 1 -2 2]"), {"path"});
    expect_identical_renders(*scene(t + " \"float frameaspectratio\" 1.5"), *scene(t), {"path"});  // the image's own
    expect_identical_renders(*scene(t + " \"float frameaspectratio\" 3 \"float screenwindow\" [-1 1 -1 1]"),
                             *scene(t + " \"float screenwindow\" [-1 1 -1 1]"), {"path"});
  }
  expect_load_error("Camera \"perspective\" \"float frameaspectratio\" 0\nWorldBegin\n", "f.pbrt",
                    {"f.pbrt:1", "\"frameaspectratio\" must be a positive number"});
}

}  // namespace
}  // namespace lantern
