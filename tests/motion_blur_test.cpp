// Motion blur: pbrt's ActiveTransform, TransformTimes and the camera's
// shutter. The interpolation against closed forms; a moving occluder's
// blurred edge against its coverage profile; the integrators against each
// other on a moving, lit scene; still scenes untouched.
#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>

#include "expect_error.h"
#include "lantern/render.h"
#include "lantern/scene.h"
#include "math/motion.h"
#include "stat_compare.h"

namespace lantern {
namespace {

double max_difference(const glm::dmat4& a, const glm::dmat4& b) {
  double d = 0.0;
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r) d = std::max(d, std::fabs(a[c][r] - b[c][r]));
  return d;
}

TEST(MotionBlur, InterpolatesTranslationLinearlyAndRotationAlongTheArc) {
  const glm::dmat4 I(1.0);
  const glm::dmat4 scale = glm::scale(I, glm::dvec3(2.0, 2.0, 2.0));
  const glm::dmat4 a = glm::translate(I, glm::dvec3(1, 2, 3)) * scale;
  const glm::dmat4 b = glm::translate(I, glm::dvec3(5, 2, -1)) * glm::rotate(I, glm::radians(90.0), glm::dvec3(0, 0, 1)) * scale;
  // Halfway: half the translation, 45 degrees, the scale kept (a
  // matrix lerp would shrink the object by cos 45 degrees).
  const glm::dmat4 half = glm::translate(I, glm::dvec3(3, 2, 1)) * glm::rotate(I, glm::radians(45.0), glm::dvec3(0, 0, 1)) * scale;
  EXPECT_LT(max_difference(interpolate_transform(a, b, 0.5), half), 1e-9);
  EXPECT_LT(max_difference(interpolate_transform(a, b, 0.0), a), 1e-12);
  EXPECT_LT(max_difference(interpolate_transform(a, b, 1.0), b), 1e-12);
  EXPECT_NEAR(rotation_angle(a, b), glm::radians(90.0), 1e-9);
  // Embree's steps: one per degree, each on pbrt's path, and between them
  // within the chord's 1 - cos(0.5 degrees) of it.
  const MotionPath path = motion_path(a, b);
  EXPECT_EQ(path.steps.size(), 91u);
  for (double u : {0.0, 0.1234, 0.5, 0.77, 1.0}) {
    const glm::dmat4 exact = interpolate_transform(a, b, u);
    EXPECT_LT(max_difference(glm::dmat4(path.at(float(u))), exact), 2.0 * 4e-5 * 6.0) << u;
  }
  // A pure translation needs no step between its ends.
  EXPECT_EQ(motion_path(a, glm::translate(I, glm::dvec3(0, 9, 0)) * a).steps.size(), 2u);
}

TEST(MotionBlur, ShutterTimesMapOntoTheTransformsMotion) {
  ShutterTimes s;
  s.open = 0.25f, s.close = 0.75f, s.start = 0.f, s.end = 0.5f;
  EXPECT_FLOAT_EQ(s.time(0.f), 0.25f);
  EXPECT_FLOAT_EQ(s.unit(s.time(0.f)), 0.5f);
  EXPECT_FLOAT_EQ(s.unit(s.time(1.f)), 1.f);  // after the end, the end transform holds
  s.start = s.end = 0.5f;
  EXPECT_FLOAT_EQ(s.unit(0.5f), 0.f);
  EXPECT_FLOAT_EQ(s.unit(0.6f), 1.f);
}

// A black quad 2 units wide moving 4 units along x in front of a white
// sky, seen by an orthographic camera 8 units wide: a pixel at x sees the
// sky for the part of the shutter the quad does not cover it,
// 1 - |[(x + 1) / 4, (x + 3) / 4] cut to [0, 1]|, a trapezoid.
std::string occluder_scene(const std::string& integrator, const std::string& shutter) {
  return R"(
Film "rgb" "integer xresolution" [ 64 ] "integer yresolution" [ 4 ]
Sampler "independent"
PixelFilter "box" "float xradius" [ 0.5 ] "float yradius" [ 0.5 ]
Integrator ")" + integrator + R"(" "integer maxdepth" [ 1 ]
LookAt 0 0 -5  0 0 0  0 1 0
Camera "orthographic" "float screenwindow" [ -4 4 -0.25 0.25 ] )" + shutter + R"(
WorldBegin
LightSource "infinite" "rgb L" [ 1 1 1 ]
AttributeBegin
  Material "diffuse" "rgb reflectance" [ 0 0 0 ]
  ActiveTransform EndTime
  Translate 4 0 0
  ActiveTransform All
  Shape "bilinearmesh" "point3 P" [ -3 -2 0  -1 -2 0  -3 2 0  -1 2 0 ]
AttributeEnd
)";
}

double sky_fraction(double x, double t0, double t1) {
  const double lo = std::max((x + 1.0) / 4.0, t0), hi = std::min((x + 3.0) / 4.0, t1);
  return 1.0 - std::max(0.0, hi - lo) / (t1 - t0);
}

void expect_coverage_profile(const std::string& integrator, const std::string& shutter, double t0, double t1) {
  auto scene = load_scene_from_string(occluder_scene(integrator, shutter), "occluder.pbrt");
  RenderOptions o;
  o.integrator = parse_integrator(integrator);
  o.spp = 1024;
  const Image img = render(*scene, o).image;
  const int n = 4 * o.spp;  // samples per column
  for (int x = 0; x < 64; ++x) {
    double sum = 0.0;
    for (int y = 0; y < 4; ++y) sum += img.at(x, y)[0];
    const double mean = sum / 4.0;
    // The pixel's average of the profile (piecewise linear: the centre's
    // value but at a kink, where the average is taken over 8 points).
    double expect = 0.0;
    for (int k = 0; k < 8; ++k) expect += sky_fraction(-4.0 + (x + (k + 0.5) / 8.0) / 8.0, t0, t1) / 8.0;
    const double sigma = std::sqrt(std::max(expect * (1.0 - expect), 0.01) / n);
    // (the image is scaled by the shutter's length, pbrt-v4's imaging ratio)
    EXPECT_NEAR(mean, expect * (t1 - t0), (5.0 * sigma + 0.01) * (t1 - t0)) << integrator << " column " << x;
  }
}

TEST(MotionBlur, AMovingOccluderBlursAsItsCoverageOverTheShutter) {
  expect_coverage_profile("path", "", 0.0, 1.0);
  expect_coverage_profile("bdpt", "", 0.0, 1.0);
  // Half the shutter: the quad covers [0.25, 0.75] of its motion.
  expect_coverage_profile("path", R"("float shutteropen" [ 0.25 ] "float shutterclose" [ 0.75 ])", 0.25, 0.75);
}

// A white quad turning and sliding under a point light, seen by a camera
// that moves too: the path tracer, bdpt, light tracing and vcm see the
// same blurred image (light subpaths share their camera sample's time).
TEST(MotionBlur, IntegratorsAgreeOnAMovingLitScene) {
  const std::string text = R"(
Film "rgb" "integer xresolution" [ 24 ] "integer yresolution" [ 16 ]
ActiveTransform StartTime
LookAt 0 1 -4  0 0 0  0 1 0
ActiveTransform EndTime
LookAt 0.5 1.2 -4  0 0 0  0 1 0
ActiveTransform All
Camera "perspective" "float fov" [ 50 ]
WorldBegin
LightSource "point" "rgb I" [ 6 6 6 ] "point3 from" [ 0 3 -1 ]
Material "diffuse" "rgb reflectance" [ 0.5 0.5 0.5 ]
Shape "trianglemesh" "point3 P" [ -5 -1 -5  5 -1 -5  5 -1 5  -5 -1 5 ] "integer indices" [ 0 1 2 0 2 3 ]
AttributeBegin
  Material "diffuse" "rgb reflectance" [ 0.8 0.3 0.2 ]
  ActiveTransform EndTime
  Translate 0.6 0 0
  Rotate 40 0 1 0
  ActiveTransform All
  Shape "bilinearmesh" "point3 P" [ -1 -0.5 0  1 -0.5 0  -1 0.8 0.3  1 0.8 0.3 ]
AttributeEnd
)";
  auto scene = load_scene_from_string(text, "moving.pbrt");
  const std::vector<Region> regions = {{0, 0, 24, 16}, {4, 4, 8, 6}, {12, 4, 8, 6}, {6, 10, 12, 4}};
  const RegionStats path = render_stats(*scene, "path", 24, 16, 64, 6, regions, false, "independent");
  const RegionStats bdpt = render_stats(*scene, "bdpt", 24, 16, 64, 6, regions, false, "independent");
  const RegionStats lt = render_stats(*scene, "lt", 24, 16, 64, 6, regions, false, "independent");
  const RegionStats vcm = render_stats(*scene, "vcm", 24, 16, 64, 6, regions, false, "independent");
  expect_means_agree(bdpt, path, 0.01, "path against bdpt");
  expect_means_agree(bdpt, lt, 0.01, "lt against bdpt");
  expect_means_agree(bdpt, vcm, 0.02, "vcm against bdpt");
  // And the blur is there: the same scene without the motion differs.
  std::string still = text;
  still.replace(still.find("  Translate 0.6"), std::string("  Translate 0.6 0 0\n  Rotate 40 0 1 0\n").size(), "");
  auto still_scene = load_scene_from_string(still, "still.pbrt");
  const RegionStats unmoved = render_stats(*still_scene, "path", 24, 16, 64, 6, regions, false, "independent");
  EXPECT_GT(max_z(path, unmoved), 8.0);
}

TEST(MotionBlur, TransformsThatDoNotMoveRenderBitIdenticallyToNoMotion) {
  const std::string a = R"(
Film "rgb" "integer xresolution" [ 16 ] "integer yresolution" [ 12 ]
LookAt 0 1 -4  0 0 0  0 1 0
Camera "perspective" "float fov" [ 50 ]
WorldBegin
LightSource "point" "rgb I" [ 6 6 6 ] "point3 from" [ 0 3 -1 ]
Translate 0.2 0 0
Shape "sphere" "float radius" [ 1 ]
)";
  std::string b = a;
  b.replace(b.find("Translate"), 0, "ActiveTransform StartTime\nTranslate 0 0 0\nActiveTransform All\n");
  auto sa = load_scene_from_string(a, "a.pbrt");
  auto sb = load_scene_from_string(b, "b.pbrt");
  expect_identical_renders(*sa, *sb, {"path", "bdpt"});
}

TEST(MotionBlur, MovingRendersAreThreadInvariant) {
  auto scene = load_scene_from_string(occluder_scene("path", ""), "occluder.pbrt");
  RenderOptions o;
  o.spp = 8;
  expect_thread_invariant(*scene, o, {"path", "bdpt", "vcm"});
}

TEST(MotionBlur, RefusesWhatItCannotRender) {
  const std::string head = "Camera \"perspective\"\nWorldBegin\n";
  expect_load_error(head + "ActiveTransform EndTime\nTranslate 1 0 0\nAreaLightSource \"diffuse\" \"rgb L\" [ 1 1 1 ]\n"
                           "Shape \"sphere\"\n",
                    "x.pbrt", {"x.pbrt:6", "a moving area light is not supported"});
  expect_load_error(head + "ObjectBegin \"o\"\nActiveTransform EndTime\nTranslate 1 0 0\nShape \"sphere\"\nObjectEnd\n",
                    "x.pbrt", {"x.pbrt:6", "a moving shape inside ObjectBegin"});
  expect_load_error(head + "ActiveTransform Sometimes\n", "x.pbrt", {"x.pbrt:3", "ActiveTransform expects StartTime, EndTime or All"});
  expect_load_error("TransformTimes 1 0\n" + head, "x.pbrt", {"x.pbrt:1", "the end time must not come before the start time"});
}

}  // namespace
}  // namespace lantern
