// pbrt-v4's realistic camera (camera/lens_system.h): a biconvex lens
// behind a stop, focused by the thick lens approximation, rays through the
// exit pupil weighted by cos^4 / (pdf z^2). Against what the lens itself
// says: a focused point is sharp, the pupil's box holds every ray that
// passes (the mean weight equals the integral over the rear plane), the
// image is upright as the perspective camera's is, and a white sky makes
// the irradiance the integral predicts.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "camera/camera.h"
#include "expect_error.h"
#include "lantern/render.h"
#include "lantern/scene.h"
#include "math/rng.h"
#include "stat_compare.h"

namespace lantern {
namespace {

// mm: a stop of 10 mm, 1 mm before a biconvex lens (radii 50 and -50, 5 mm
// of glass of index 1.5): focal length about 49 mm.
const char* kLens = R"(# radius thickness eta aperture
0    1  0    10
50   5  1.5  20   # front face
-50  0  1    20
)";

std::string lens_file() {
  const auto dir = std::filesystem::temp_directory_path() / ("lantern-lens-test-" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  const std::string path = (dir / "biconvex.dat").string();
  std::ofstream(path) << kLens;
  return path;
}

LensSystem focused_lens(float distance) {
  LensSystem lens(read_lens_file(lens_file()), 10.f);
  lens.focus(distance, 0.001f * 0.035f);
  lens.compute_exit_pupil(0.5f * 0.035f);
  return lens;
}

TEST(RealisticCamera, AFocusedPointIsSharp) {
  for (const float distance : {0.5f, 2.f, 10.f}) {
    const LensSystem lens = focused_lens(distance);
    // Rays from the film's centre through points of the pupil near the
    // axis leave converging on the axis at the focus distance (from the
    // film, as pbrt-v4 measures it). Spherical aberration moves the
    // crossing as the square of the height (a millimetre off the axis:
    // 11% at 10 m, for this f/5 singlet), so paraxial rays, within 1%.
    for (const float h : {0.02e-3f, 0.05e-3f, 0.1e-3f}) {
      const LensRay from_film{Vec3(0.f), Vec3(h, 0.f, lens.rear_z())};
      const std::optional<LensRay> out = lens.trace_from_film(from_film);
      ASSERT_TRUE(out) << h;
      ASSERT_LT(out->d.x, 0.f) << "the ray does not turn back to the axis";
      const float t = -out->o.x / out->d.x;
      EXPECT_NEAR(out->o.z + t * out->d.z, distance, 0.01f * distance) << "height " << h << ", focus " << distance;
    }
  }
}

// The weight's mean over the pupil box is the integral of cos^4 / z^2 over
// the rear plane's points that pass, taken here on a fine grid with the
// lens's own tracing: a box that missed part of the pupil would fall short.
TEST(RealisticCamera, PupilBoxHoldsEveryPassingRay) {
  const LensSystem lens = focused_lens(2.f);
  for (const float r_film : {0.f, 0.006f, 0.012f}) {
    const Vec3 p_film(r_film * 0.6f, r_film * 0.8f, 0.f);
    const float half = 1.5f * lens.rear_radius(), step = 2.f * half / 400.f;
    double integral = 0.0;
    for (int j = 0; j < 400; ++j)
      for (int i = 0; i < 400; ++i) {
        const Vec3 rear(-half + (float(i) + 0.5f) * step, -half + (float(j) + 0.5f) * step, lens.rear_z());
        if (!lens.trace_from_film({p_film, rear - p_film})) continue;
        const float c = glm::normalize(rear - p_film).z;
        integral += double(sqr(c) * sqr(c)) / double(sqr(lens.rear_z())) * double(step) * double(step);
      }
    ASSERT_GT(integral, 0.0) << r_film;
    double sum = 0.0, sum2 = 0.0;
    const int n = 1 << 16;
    for (int k = 0; k < n; ++k) {
      RandomStream r = RandomStream::make(7, uint64_t(k), uint64_t(r_film * 1e6f));
      const auto s = lens.sample_ray(p_film, Vec2(r.get1d(), r.get1d()));
      const double w = s ? double(s->weight) : 0.0;
      sum += w;
      sum2 += w * w;
    }
    const double mean = sum / n, se = std::sqrt(std::max(0.0, sum2 / n - mean * mean) / n);
    EXPECT_NEAR(mean, integral, 4.0 * se + 0.01 * integral) << "film radius " << r_film;
  }
}

std::string realistic_scene(const std::string& world, const std::string& camera_params = "") {
  return "LookAt 0 0 0  0 0 1  0 1 0\nCamera \"realistic\" \"string lensfile\" \"" + lens_file() +
         "\" \"float aperturediameter\" 10 \"float focusdistance\" 5 " + camera_params +
         "\nFilm \"rgb\" \"integer xresolution\" 16 \"integer yresolution\" 12\nSampler \"halton\"\nWorldBegin\n" +
         world;
}

// A white sky: the centre pixels' irradiance is the rear-plane integral
// at the film's centre (4 x 4 pixels there: within 2% of it).
TEST(RealisticCamera, WhiteSkyGivesTheIrradianceOfThePupil) {
  auto scene = load_scene_from_string(realistic_scene("LightSource \"infinite\" \"rgb L\" [1 1 1]\n"), "r.pbrt", {});
  RenderOptions o;
  o.spp = 64;
  const RegionStats st = stats_of(render_runs(*scene, o, 4, 1), {{6, 4, 4, 4}});
  const LensSystem lens = focused_lens(5.f);
  const float half = 1.5f * lens.rear_radius(), step = 2.f * half / 400.f;
  double integral = 0.0;
  for (int j = 0; j < 400; ++j)
    for (int i = 0; i < 400; ++i) {
      const Vec3 rear(-half + (float(i) + 0.5f) * step, -half + (float(j) + 0.5f) * step, lens.rear_z());
      if (!lens.trace_from_film({Vec3(0.f), rear})) continue;
      const float c = glm::normalize(rear).z;
      integral += double(sqr(c) * sqr(c)) / double(sqr(lens.rear_z())) * double(step) * double(step);
    }
  for (size_t c = 0; c < 3; ++c) EXPECT_NEAR(st.mean[0][c], integral, 4.0 * st.std_error[0][c] + 0.02 * integral) << c;
}

// An emitter on the camera's right (+x, whose raster x grows with camera x)
// lights the image's right half, as with the perspective camera: the lens
// turns the image over and the film is read turned back.
TEST(RealisticCamera, ImageIsUprightAsThePerspectiveCamerasIs) {
  const std::string world =
      "AttributeBegin\nAreaLightSource \"diffuse\" \"rgb L\" [1 1 1]\n"
      "Shape \"trianglemesh\" \"point3 P\" [0.2 -3 5  8 -3 5  8 5 5  0.2 5 5] "
      "\"integer indices\" [0 2 1 0 3 2]\nAttributeEnd\n";
  for (const bool realistic : {true, false}) {
    std::string text = realistic_scene(world);
    if (!realistic)
      text.replace(text.find("Camera"), text.find('\n', text.find("Camera")) - text.find("Camera"),
                   "Camera \"perspective\" \"float fov\" 30");
    auto scene = load_scene_from_string(text, "r.pbrt", {});
    RenderOptions o;
    o.spp = 16;
    const RegionStats st = stats_of(render_runs(*scene, o, 1, 1), {{0, 0, 8, 12}, {8, 0, 8, 12}, {0, 0, 16, 6}});
    EXPECT_GT(st.mean[1][0], 4.0 * st.mean[0][0] + 1e-6) << (realistic ? "realistic" : "perspective") << ": right half";
    // The emitter reaches higher (camera +y, the image's top) than below.
    EXPECT_GT(st.mean[2][0], 0.0) << (realistic ? "realistic" : "perspective");
  }
}

TEST(RealisticCamera, BadLensesAndIntegratorsAreRefused) {
  expect_load_error("Camera \"realistic\"\n", "c.pbrt", {"c.pbrt:1", "lensfile"});
  const auto dir = std::filesystem::path(lens_file()).parent_path();
  std::ofstream(dir / "bad.dat") << "0 1 0 10\n50 5 1.5 twenty\n";
  expect_load_error("Camera \"realistic\" \"string lensfile\" \"" + (dir / "bad.dat").string() + "\"\n", "c.pbrt",
                    {"c.pbrt:1", "bad.dat:2", "twenty"});
  std::ofstream(dir / "odd.dat") << "0 1 0 10\n50 5 1.5\n";
  expect_load_error("Camera \"realistic\" \"string lensfile\" \"" + (dir / "odd.dat").string() + "\"\n", "c.pbrt",
                    {"four numbers"});
  // Closer than the lens can focus (inside its focal length): at load,
  // with the Camera's line.
  expect_load_error("Film \"rgb\"\nCamera \"realistic\" \"string lensfile\" \"" + lens_file() +
                        "\"\n  \"float focusdistance\" 0.02\nWorldBegin\n",
                    "f.pbrt", {"f.pbrt:3", "cannot focus", "focusdistance"});
  auto scene = load_scene_from_string(realistic_scene("LightSource \"infinite\"\n"), "r.pbrt", {});
  RenderOptions o;
  o.spp = 1;
  o.integrator = Integrator::Bdpt;
  try {
    render(*scene, o);
    ADD_FAILURE() << "bdpt rendered with a realistic camera";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("realistic camera works with path"), std::string::npos) << e.what();
  }
}

// pbrt-v4's aperture shapes: each lets as much light through as the round
// stop (their means are pi / 4 of the stop's square), oriented as pbrt-v4
// flips its images (the pentagon's vertex at -y on the stop), and an image
// file's top row towards +y.
TEST(RealisticCamera, ApertureShapesPassTheRoundStopsLight) {
  auto mean_weight = [](const LensSystem& lens) {
    RandomStream s = RandomStream::make(8, 0, 0);
    double sum = 0.0;
    const int n = 200000;
    for (int i = 0; i < n; ++i)
      if (auto r = lens.sample_ray(Vec3(0.f), s.get2d())) sum += r->weight;
    return sum / n;
  };
  const double round = mean_weight(focused_lens(2.f));
  for (const char* name : {"gaussian", "square", "pentagon", "star"}) {
    const std::optional<ApertureMask> mask = builtin_aperture(name);
    ASSERT_TRUE(mask) << name;
    double sum = 0.0;
    for (float v : mask->values) sum += v;
    EXPECT_NEAR(sum / double(mask->values.size()), kPi / 4.0, 1e-4) << name;
    LensSystem lens = focused_lens(2.f);
    lens.set_aperture(*mask);
    EXPECT_NEAR(mean_weight(lens), round, 0.03 * round) << name;
  }
  const ApertureMask pentagon = *builtin_aperture("pentagon");
  EXPECT_GT(pentagon.at(Vec2(0.f, -0.75f)), 0.f);
  EXPECT_EQ(pentagon.at(Vec2(0.f, 0.7f)), 0.f);
  EXPECT_FALSE(builtin_aperture("hexagon"));

  // An image: white in its top half only.
  const auto dir = std::filesystem::path(lens_file()).parent_path();
  Image img;
  img.width = img.height = 8;
  img.rgb.assign(8 * 8 * 3, 0.f);
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < 8; ++x) img.at(x, y)[0] = img.at(x, y)[1] = img.at(x, y)[2] = 1.f;
  write_image((dir / "half.png").string(), img, {});
  auto scene = load_scene_from_string("Camera \"realistic\" \"string lensfile\" \"" + lens_file() +
                                          "\" \"float aperturediameter\" 10 \"string aperture\" \"" +
                                          (dir / "half.png").string() + "\"\nWorldBegin\n",
                                      "a.pbrt", {});
  LensSystem lens = *scene->camera.lens;
  lens.focus(2.f, 0.001f * 0.035f);
  lens.compute_exit_pupil(0.5f * 0.035f);
  RandomStream s = RandomStream::make(9, 0, 0);
  int up = 0, down = 0;
  for (int i = 0; i < 20000; ++i)
    if (auto r = lens.sample_ray(Vec3(0.f), s.get2d()); r && r->weight > 0.f) {
      if (r->ray.o.y > 0.001f) ++up;     // the stop's radius is 5 mm; its texels
      if (r->ray.o.y < -0.001f) ++down;  // blend within 0.6 mm of y = 0
    }
  EXPECT_GT(up, 1000);
  EXPECT_EQ(down, 0) << "the ray leaves from the stop (the front interface), so its y is the stop's";
  expect_load_error("Camera \"realistic\" \"string lensfile\" \"" + lens_file() +
                        "\" \"string aperture\" \"nothing.png\"\nWorldBegin\n",
                    "a.pbrt", {"a.pbrt:1", "nothing.png", "gaussian, square, pentagon, star"});
}

}  // namespace
}  // namespace lantern
