// Participating media against closed forms: transmittance along camera rays
// and along shadow rays, single scattering of a point light in an unbounded
// medium (against its integral), a white furnace (a non-absorbing medium
// inside an emitter of radiance 1 is lit to exactly 1), and the errors bad
// media input gets.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "expect_error.h"
#include "lantern/render.h"
#include "lantern/scene.h"
#include "media_scenes.h"
#include "sanitizer.h"
#include "scene/scene.h"
#include "stat_compare.h"

namespace lantern {
namespace {

RenderOptions small_path_render(int width, int height, int spp, int maxdepth, const char* integrator = "path") {
  RenderOptions o;
  o.integrator = parse_integrator(integrator);
  o.width = width;
  o.height = height;
  o.spp = spp;
  o.maxdepth = maxdepth;
  return o;
}

std::array<double, 3> image_mean(const Image& img) {
  std::array<double, 3> m{};
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x)
      for (int c = 0; c < 3; ++c) m[size_t(c)] += img.at(x, y)[c];
  for (double& v : m) v /= double(img.width * img.height);
  return m;
}

// A slab 2 units thick (tests/media_scenes.h) before an emitter of radiance 1.
const std::string kSlab = slab_scene(R"(MakeNamedMedium "slab" "string type" "homogeneous"
  "rgb sigma_a" [ 0.1 0.4 0.9 ] "rgb sigma_s" [ 0.2 0.2 0.2 ])");

// Camera rays: with maxdepth 0 a ray that scatters ends, so each pixel's
// expected value is exp(-sigma_t d). Each sample is 0 or T_c / P (P = the
// mean of the channels' T); the tolerance is 5 standard errors of that.
TEST(Media, SlabTransmittanceAlongCameraRays) {
  auto scene = load_scene_from_string(kSlab, "slab.pbrt", {});
  const int spp = LANTERN_ASAN ? 16 : 128;
  RenderResult r = render(*scene, small_path_render(32, 32, spp, 0));
  const std::array<double, 3> mean = image_mean(r.image);
  const double sigma_t[3] = {0.3, 0.6, 1.1};
  double T[3], P = 0.0;
  for (int c = 0; c < 3; ++c) P += (T[c] = std::exp(-2.0 * sigma_t[c])) / 3.0;
  const double n = 32.0 * 32.0 * spp;
  for (int c = 0; c < 3; ++c) {
    const double se = std::sqrt((T[c] * T[c] / P - T[c] * T[c]) / n);
    EXPECT_NEAR(mean[size_t(c)], T[c], 5.0 * se) << "channel " << c;
  }
}

// Shadow rays: a wall lit by a point light inside an absorbing ball of
// radius 0.5 (out of the camera's view). Every shadow ray crosses 0.5 of
// the medium, so with direct light only the image is exactly exp(-0.5
// sigma_t) times the image without the medium, pixel by pixel.
std::string lit_wall(const std::string& ball_medium) {
  return R"(
PixelFilter "box"
LookAt 0 0 0  0 0 1  0 1 0
Camera "perspective" "float fov" [ 10 ]
WorldBegin
MakeNamedMedium "ink" "string type" "homogeneous"
  "rgb sigma_a" [ 0.5 1.0 2.0 ] "rgb sigma_s" [ 0.5 0.5 0.5 ]
Material "diffuse" "rgb reflectance" [ 0.5 0.5 0.5 ]
Shape "trianglemesh" "point3 P" [ -10 -10 5  -10 10 5  10 10 5  10 -10 5 ] "integer indices" [ 0 1 2 0 2 3 ]
AttributeBegin
  MediumInterface ")" + ball_medium + R"(" ""
  Material "interface"
  Translate 0 2 3
  Shape "sphere" "float radius" [ 0.5 ]
AttributeEnd
AttributeBegin
  MediumInterface ")" + ball_medium + R"("
  LightSource "point" "point3 from" [ 0 2 3 ] "rgb I" [ 20 20 20 ]
AttributeEnd
)";
}

TEST(Media, SlabTransmittanceAlongShadowRays) {
  auto with = load_scene_from_string(lit_wall("ink"), "ink.pbrt", {});
  auto without = load_scene_from_string(lit_wall(""), "clear.pbrt", {});
  RenderOptions o = small_path_render(16, 16, 4, 1);
  Image a = render(*with, o).image, b = render(*without, o).image;
  const double sigma_t[3] = {1.0, 1.5, 2.5};
  double largest = 0.0;
  for (int y = 0; y < 16; ++y)
    for (int x = 0; x < 16; ++x)
      for (int c = 0; c < 3; ++c) {
        ASSERT_GT(b.at(x, y)[c], 0.f);
        largest = std::max(largest, std::fabs(a.at(x, y)[c] / b.at(x, y)[c] / std::exp(-0.5 * sigma_t[c]) - 1.0));
      }
  EXPECT_LT(largest, 1e-4) << "largest relative departure from exp(-sigma_t r)";
}

// Single scattering: the camera and a point light in an unbounded medium;
// with maxdepth 1 a pixel sees exactly the light scattered once towards it:
//   L(d) = integral_0^inf T(t) sigma_s p(d . l(t)) I T(r(t)) / r(t)^2 dt.
// The image mean is that integral averaged over the film (box filter).
// Every integrator: path (next-event estimation from the medium vertex),
// bdpt (that, and the light vertex in the medium connected to the camera,
// weighted by MIS) and lt (the latter alone).
class MediaIntegrators : public ::testing::TestWithParam<const char*> {};
INSTANTIATE_TEST_SUITE_P(Media, MediaIntegrators, ::testing::Values("path", "bdpt", "lt"));

TEST_P(MediaIntegrators, SingleScatteringOfAPointLightMatchesItsIntegral) {
  const char* text = R"(
PixelFilter "box"
MediumInterface "" "mist"
LookAt 0 0 0  0 0 1  0 1 0
Camera "perspective" "float fov" [ 20 ]
WorldBegin
MakeNamedMedium "mist" "string type" "homogeneous"
  "rgb sigma_a" [ 0.05 0.1 0.2 ] "rgb sigma_s" [ 0.3 0.2 0.1 ] "float g" [ 0.5 ]
MediumInterface "" "mist"
LightSource "point" "point3 from" [ 1 0 3 ] "rgb I" [ 10 10 10 ]
)";
  auto scene = load_scene_from_string(text, "mist.pbrt", {});
  const int spp = std::string(GetParam()) == "lt" ? 256 : 64;
  const RegionStats st = stats_of(render_runs(*scene, small_path_render(8, 8, spp, 1, GetParam()), 4, 1), {{0, 0, 8, 8}});
  const double sa[3] = {0.05, 0.1, 0.2}, ss[3] = {0.3, 0.2, 0.1}, g = 0.5, I = 10.0;
  const double half = std::tan(10.0 * kPi / 180.0);
  for (int c = 0; c < 3; ++c) {
    const double st_c = sa[c] + ss[c];
    double film_sum = 0.0;
    const int kFilm = 16, kSteps = 6000;
    const double t_end = 40.0 / st_c, dt = t_end / kSteps;
    for (int fy = 0; fy < kFilm; ++fy)
      for (int fx = 0; fx < kFilm; ++fx) {
        glm::dvec3 d((2.0 * (fx + 0.5) / kFilm - 1.0) * half, (2.0 * (fy + 0.5) / kFilm - 1.0) * half, 1.0);
        d = glm::normalize(d);
        double sum = 0.0;
        for (int k = 0; k <= kSteps; ++k) {  // Simpson's rule
          const double t = k * dt;
          const glm::dvec3 to_light = glm::dvec3(1, 0, 3) - t * d;
          const double r2 = glm::dot(to_light, to_light), r = std::sqrt(r2);
          const double cos_t = glm::dot(d, to_light / r);
          const double phase = (1 - g * g) / (4 * kPi * std::pow(1 + g * g - 2 * g * cos_t, 1.5));
          const double f = std::exp(-st_c * (t + r)) * ss[c] * phase * I / r2;
          sum += f * (k == 0 || k == kSteps ? 1.0 : k % 2 ? 4.0 : 2.0);
        }
        film_sum += sum * dt / 3.0;
      }
    const double expected = film_sum / (kFilm * kFilm);
    EXPECT_LT(std::fabs(st.mean[0][size_t(c)] - expected), 4.0 * st.std_error[0][size_t(c)] + 0.003 * expected)
        << "channel " << c << ": " << st.mean[0][size_t(c)] << " against " << expected;
  }
}

// A white furnace: inside a sphere that emits radiance 1 inwards and
// reflects nothing, a medium that scatters (differently per channel) but
// absorbs nothing leaves radiance 1 everywhere; the camera sits inside.
// The channels differ moderately: per-segment channel sampling gives a
// strongly coloured medium heavy-tailed weights after many scatterings
// (docs/media.md), which a few samples per pixel underestimate.
// (Light tracing is left out: with the camera inside a scattering medium,
// its camera connections from vertices near the lens grow as 1/r^2, and
// their variance is infinite.)
TEST_P(MediaIntegrators, WhiteFurnaceStaysAtOne) {
  if (std::string(GetParam()) == "lt") GTEST_SKIP() << "infinite variance (see above)";
  const char* text = R"(
PixelFilter "box"
MediumInterface "fog" "fog"
LookAt 0 0 0  0 0 1  0 1 0
Camera "perspective" "float fov" [ 60 ]
WorldBegin
MakeNamedMedium "fog" "string type" "homogeneous"
  "rgb sigma_a" [ 0 0 0 ] "rgb sigma_s" [ 0.7 1 1.4 ] "float g" [ 0.3 ]
AttributeBegin
  # ReverseOrientation turns the normal inwards, and with it pbrt's
  # "outside" side: the fog is on the outside of the reversed sphere.
  MediumInterface "" "fog"
  ReverseOrientation
  AreaLightSource "diffuse" "rgb L" [ 1 1 1 ]
  Material "diffuse" "rgb reflectance" [ 0 0 0 ]
  Shape "sphere" "float radius" [ 1 ]
AttributeEnd
)";
  auto scene = load_scene_from_string(text, "furnace.pbrt", {});
  const int spp = LANTERN_ASAN ? 8 : 32;
  const RegionStats st =
      stats_of(render_runs(*scene, small_path_render(16, 16, spp, 100, GetParam()), 4, 1), {{0, 0, 16, 16}});
  for (int c = 0; c < 3; ++c)
    EXPECT_LT(std::fabs(st.mean[0][size_t(c)] - 1.0), 4.0 * st.std_error[0][size_t(c)] + 1e-3)
        << "channel " << c << ": " << st.mean[0][size_t(c)];
}

TEST(Media, ImagesDoNotDependOnThreads) {
  auto scene = load_scene(std::string(LANTERN_SOURCE_DIR) + "/perf/media/fog-sphere.pbrt");
  RenderOptions o = small_path_render(40, 30, 4, 10);
  expect_thread_invariant(*scene, o, {"path", "bdpt", "lt"});
}

// pbrt-v4 (a CPU Release build of its public source, volpath) rendered perf/media/fog-sphere.pbrt
// at 80x60 with 256 spp; these are its means of the fog ball (20x15 at
// 30,15) and of the whole image (oiiotool --cut ... --printstats). The
// allowance covers pbrt's spectral, not RGB, extinction (docs/media.md).
TEST(Media, FogSphereMatchesPbrt) {
  if (LANTERN_ASAN) GTEST_SKIP() << "the Release suite runs it";
  auto scene = load_scene(std::string(LANTERN_SOURCE_DIR) + "/perf/media/fog-sphere.pbrt");
  expect_matches_pbrt(*scene, 80, 60, 20, 64, 4, {{30, 15, 20, 15}, {0, 0, 80, 60}},
                      {{0.134514, 0.153802, 0.177175}, {0.060969, 0.060730, 0.061208}}, 0.025);
}

TEST(Media, BadInputIsRefusedWithItsLine) {
  const std::string head = "LookAt 0 0 0 0 0 1 0 1 0\nCamera \"perspective\"\nWorldBegin\n";
  expect_load_error(head + "MakeNamedMedium \"m\" \"string type\" \"fluffy\"\n", "a.pbrt",
                    {"a.pbrt:4", "unknown medium type \"fluffy\"", "homogeneous"});
  expect_load_error(head + "MakeNamedMedium \"m\" \"float g\" 0.2\n", "b.pbrt", {"b.pbrt:4", "string type"});
  expect_load_error(head + "MakeNamedMedium \"m\" \"string type\" \"homogeneous\" \"rgb sigma_a\" [ 1 -1 1 ]\n",
                    "c.pbrt", {"c.pbrt:4", "sigma_a", "negative"});
  expect_load_error(head + "MakeNamedMedium \"m\" \"string type\" \"homogeneous\" \"float scale\" -2\n", "d.pbrt",
                    {"d.pbrt", "\"scale\" must be finite and not negative"});
  expect_load_error(head + "MakeNamedMedium \"m\" \"string type\" \"homogeneous\" \"float g\" 1\n", "e.pbrt",
                    {"e.pbrt:4", "\"g\" must lie strictly between -1 and 1"});
  expect_load_error(head + "MakeNamedMedium \"m\" \"string type\" \"homogeneous\" \"string preset\" \"Tea\"\n",
                    "f.pbrt", {"f.pbrt:4", "unknown preset \"Tea\"", "Wholemilk"});
  expect_load_error(head + "MediumInterface \"smoke\" \"\"\nShape \"sphere\"\n", "g.pbrt",
                    {"g.pbrt:4", "medium \"smoke\" is not defined"});
  expect_load_error(head + "MakeNamedMedium \"m\" \"string type\" \"homogeneous\"\n"
                           "MakeNamedMedium \"m\" \"string type\" \"homogeneous\"\n",
                    "h.pbrt", {"h.pbrt:5", "defined twice"});
  expect_load_error(head + "MakeNamedMedium \"m\" \"string type\" \"homogeneous\" \"rgb Le\" [ 1 -1 1 ]\n", "i.pbrt",
                    {"i.pbrt:4", "\"Le\"", "must not be negative"});
  expect_load_error(head + "MakeNamedMedium \"m\" \"string type\" \"cloud\" \"rgb Le\" [ 1 1 1 ]\n", "l.pbrt",
                    {"l.pbrt:4", "\"Le\" is not a parameter of a cloud medium"});
  expect_load_error(head + "MakeNamedMedium \"m\" \"string type\" \"fog\"\n", "j.pbrt",
                    {"j.pbrt:4", "unknown medium type \"fog\"", "rgbgrid, cloud, nanovdb or pbrt-v3's heterogeneous"});
  expect_load_error("MediumInterface \"air\"\nLookAt 0 0 0 0 0 1 0 1 0\nCamera \"perspective\"\nWorldBegin\n", "k.pbrt",
                    {"k.pbrt:1", "medium \"air\" is not defined"});
}

TEST(Media, PresetsUsePublishedCoefficients) {
  // Jensen et al. 2001, table 2: skim milk sigma_s' = (0.70, 1.22, 1.90),
  // sigma_a = (0.0014, 0.0025, 0.0142) per mm; "scale" converts units.
  auto scene = load_scene_from_string(
      "LookAt 0 0 0 0 0 1 0 1 0\nCamera \"perspective\"\nWorldBegin\n"
      "MakeNamedMedium \"m\" \"string type\" \"homogeneous\" \"string preset\" \"Skimmilk\" \"float scale\" 10\n",
      "p.pbrt", {});
  ASSERT_EQ(scene->media.homogeneous.size(), 1u);
  const HomogeneousMedium& m = scene->media.homogeneous[0];
  EXPECT_FLOAT_EQ(m.sigma_s[1], 12.2f);
  EXPECT_FLOAT_EQ(m.sigma_a[2], 0.142f);
}

}  // namespace
}  // namespace lantern
