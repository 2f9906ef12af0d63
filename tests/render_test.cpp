// Whole-renderer checks against closed-form answers, with tolerances from
// the pixels' own sample variance, and determinism across thread counts.
#include <gtest/gtest.h>

#include <cmath>

#include "lantern/render.h"
#include "lantern/scene.h"
#include "math/common.h"

namespace lantern {
namespace {

struct Mean {
  double value[3];
  double std_error[3];
};

// Mean over all pixels; pixels are independent estimates, so the standard
// error comes from their spread.
Mean image_mean(const Image& img) {
  Mean m{};
  size_t n = size_t(img.width) * size_t(img.height);
  for (int c = 0; c < 3; ++c) {
    double s = 0.0, s2 = 0.0;
    for (size_t i = 0; i < n; ++i) {
      double v = img.rgb[3 * i + size_t(c)];
      s += v;
      s2 += v * v;
    }
    m.value[c] = s / double(n);
    m.std_error[c] = std::sqrt(std::max(0.0, s2 / double(n) - m.value[c] * m.value[c]) / double(n));
  }
  return m;
}

RenderResult render_string(const std::string& scene_text, int spp, int maxdepth, int threads = 0, uint64_t seed = 1,
                           const std::string& backend = "stream") {
  auto scene = load_scene_from_string(scene_text, "test.pbrt");
  RenderOptions o;
  o.spp = spp;
  o.maxdepth = maxdepth;
  o.threads = threads;
  o.seed = seed;
  o.ray_backend = parse_ray_backend(backend);
  return render(*scene, o);
}

void expect_mean(const Image& img, RGB expected, double k_sigma, const std::string& what) {
  Mean m = image_mean(img);
  for (int c = 0; c < 3; ++c)
    EXPECT_NEAR(m.value[c], expected[c], k_sigma * m.std_error[c] + 1e-4 * expected[c])
        << what << " channel " << c << " (std error " << m.std_error[c] << ")";
}

// A camera inside a closed diffuse sphere of albedo rho that emits L on its
// inside sees L * sum_{k=0..maxdepth} rho^k: paths of k bounces carry rho^k.
std::string furnace_sphere(float rho, float L, float radius) {
  char buf[512];
  std::snprintf(buf, sizeof buf, R"(
Film "rgb" "integer xresolution" 24 "integer yresolution" 24
LookAt 0 0 0  0 0 1  0 1 0
Camera "perspective" "float fov" 60
WorldBegin
Material "diffuse" "rgb reflectance" [%g %g %g]
AreaLightSource "diffuse" "rgb L" [%g %g %g]
ReverseOrientation
Shape "sphere" "float radius" %g
)",
                rho, rho, rho, L, L, L, radius);
  return buf;
}

TEST(Render, FurnaceSphereMatchesClosedForm) {
  const float rho = 0.6f, L = 2.f;
  for (int maxdepth : {0, 1, 3, 8}) {
    double expected = 0.0;
    for (int k = 0; k <= maxdepth; ++k) expected += L * std::pow(rho, k);
    RenderResult r = render_string(furnace_sphere(rho, L, 1.f), 16, maxdepth);
    expect_mean(r.image, RGB(float(expected)), 4.0, "maxdepth " + std::to_string(maxdepth));
    EXPECT_EQ(r.stats.nonfinite_samples, 0u);
  }
}

TEST(Render, FurnaceSphereIsScaleInvariant) {
  // Radiance does not depend on the size of the enclosure.
  for (float radius : {1e-3f, 1e3f}) {
    RenderResult r = render_string(furnace_sphere(0.5f, 1.f, radius), 16, 4);
    expect_mean(r.image, RGB(1.f + 0.5f + 0.25f + 0.125f + 0.0625f), 4.0, "radius " + std::to_string(radius));
  }
}

// A diffuse plane under a constant sky of radiance L reflects rho * L: the
// plane sees only the sky, never itself.
TEST(Render, DiffusePlaneUnderConstantSky) {
  const char* scene = R"(
Film "rgb" "integer xresolution" 24 "integer yresolution" 24
LookAt 0 1 0  0 0 0.01  0 1 0
Camera "perspective" "float fov" 40
WorldBegin
LightSource "infinite" "rgb L" [1.5 1 0.5]
Material "diffuse" "rgb reflectance" [0.5 0.25 0.8]
Shape "trianglemesh" "point3 P" [-1000 0 -1000  1000 0 -1000  1000 0 1000  -1000 0 1000]
    "integer indices" [0 1 2 0 2 3]
)";
  for (int maxdepth : {1, 5}) {
    RenderResult r = render_string(scene, 16, maxdepth);
    expect_mean(r.image, RGB(0.75f, 0.25f, 0.4f), 4.0, "maxdepth " + std::to_string(maxdepth));
  }
}

// A point light of intensity I at height h over a diffuse plane: the point
// straight below reflects rho / pi * I / h^2.
TEST(Render, PointLightOverPlane) {
  const char* scene = R"(
Film "rgb" "integer xresolution" 1 "integer yresolution" 1
PixelFilter "box" "float xradius" 0.5 "float yradius" 0.5
LookAt 0 1 0  0 0 0  0 0 1
Camera "perspective" "float fov" 0.01
WorldBegin
LightSource "point" "rgb I" [8 4 2] "point3 from" [0 2 0]
Material "diffuse" "rgb reflectance" [0.5 0.5 0.5]
Shape "trianglemesh" "point3 P" [-10 0 -10  10 0 -10  10 0 10  -10 0 10]
    "integer indices" [0 1 2 0 2 3]
)";
  RenderResult r = render_string(scene, 4, 3);
  const float* px = r.image.at(0, 0);
  RGB expected = RGB(8, 4, 2) * (0.5f / 3.14159265358979f / 4.f);
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(px[c], expected[c], 1e-3f * expected[c]);
}

std::shared_ptr<Scene> shipped_cornell_box() {
  return load_scene(std::string(LANTERN_SOURCE_DIR) + "/scenes/cornell-box.pbrt");
}

TEST(Render, SameSeedSameImageWithOneOrTwoThreads) {
  auto scene = shipped_cornell_box();
  RenderOptions o;
  o.spp = 4;
  o.width = o.height = 48;
  o.wave_size = 512;
  o.threads = 1;
  Image a = render(*scene, o).image;
  o.threads = 2;
  Image b = render(*scene, o).image;
  ASSERT_EQ(a.rgb.size(), b.rgb.size());
  EXPECT_TRUE(a.rgb == b.rgb) << "images differ between 1 and 2 threads";
  o.seed = 99;
  Image c = render(*scene, o).image;
  EXPECT_FALSE(a.rgb == c.rgb) << "a different seed must give a different image";
}

TEST(Render, RayBackendsAgree) {
  auto scene = shipped_cornell_box();
  RenderOptions o;
  o.spp = 8;
  o.width = o.height = 32;
  Mean ref{};
  for (const char* b : {"stream", "stream-1m", "single", "packet16"}) {
    o.ray_backend = parse_ray_backend(b);
    RenderResult r = render(*scene, o);
    Mean m = image_mean(r.image);
    if (std::string(b) == "stream") {
      ref = m;
      continue;
    }
    // Same rays, same hits up to Embree's tie-breaking: means agree closely.
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(m.value[c], ref.value[c], 0.01 * ref.value[c]) << b;
  }
}

// Words that name no choice are refused where they are parsed, with the
// words that would do; a value outside an enumeration (a cast, bindings)
// is refused by render().
TEST(Render, BadOptionsAreRejected) {
  auto scene = load_scene_from_string(furnace_sphere(0.5f, 1.f, 1.f), "test.pbrt");
  try {
    parse_integrator("nonsense");
    ADD_FAILURE() << "an unknown integrator was accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("expected path, bdpt, lt, vcm, bpm, ppm, directlighting, ambientocclusion or mlt"), std::string::npos) << e.what();
  }
  EXPECT_THROW(parse_ray_backend("warp"), std::invalid_argument);
  EXPECT_THROW(parse_mis("heuristic"), std::invalid_argument);
  EXPECT_THROW(parse_light_sampler("exhaustive"), std::invalid_argument);
  EXPECT_EQ(parse_integrator(name(Integrator::Bpm)), Integrator::Bpm);
  EXPECT_EQ(parse_ray_backend("stream-np"), RayBackend::StreamNp);
  RenderOptions o;
  o.integrator = Integrator(200);
  EXPECT_THROW(render(*scene, o), std::invalid_argument);
  o.integrator = Integrator::Path;
  o.ray_backend = RayBackend(9);
  EXPECT_THROW(render(*scene, o), std::invalid_argument);
}

}  // namespace
}  // namespace lantern
