// An image environment light over a diffuse plane: the plane reflects
// rho/pi * E, with the irradiance E integrated independently over the map's
// texels. Exercises the equal-area and lat-long mappings and their
// importance sampling (a wrong pdf biases the MIS-weighted sum).
#include <gtest/gtest.h>

#include <filesystem>

#include "lantern/render.h"
#include "lantern/scene.h"
#include "light/lights.h"

namespace lantern {
namespace {

float texel_value(int x, int y, int w, int h) {
  return 0.1f + 3.f * float(x) / float(w) + (y < h / 4 ? 5.f : 0.f);  // a gradient and a bright band
}

double irradiance_up(int w, int h, bool equal_area) {
  // Riemann sum over texels with 8x8 points each; +y is "up" for the plane.
  double E = 0.0;
  const int k = 8;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      for (int a = 0; a < k; ++a)
        for (int b = 0; b < k; ++b) {
          Vec2 uv((x + (a + 0.5f) / k) / w, (y + (b + 0.5f) / k) / h);
          Vec3 d;
          double dw;
          if (equal_area) {
            d = equal_area_square_to_sphere(uv);
            dw = 4.0 * kPi / (double(w) * h * k * k);
          } else {
            float theta = uv.y * kPi, phi = uv.x * 2.f * kPi;
            d = Vec3(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta));
            dw = 2.0 * kPi * kPi * std::sin(theta) / (double(w) * h * k * k);
          }
          E += texel_value(x, y, w, h) * std::max(0.f, d.y) * dw;
        }
  return E;
}

TEST(EnvironmentMap, PlaneReflectsIntegratedIrradiance) {
  auto dir = std::filesystem::temp_directory_path() / "lantern-envmap-test";
  std::filesystem::create_directories(dir);
  for (bool equal_area : {true, false}) {
    int w = equal_area ? 32 : 64, h = 32;
    Image img;
    img.width = w;
    img.height = h;
    img.rgb.resize(size_t(w) * h * 3);
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x)
        for (int c = 0; c < 3; ++c) img.at(x, y)[c] = texel_value(x, y, w, h);
    std::string file = (dir / (equal_area ? "ea.exr" : "ll.exr")).string();
    write_image(file, img, {});
    std::string scene = "Film \"rgb\" \"integer xresolution\" 16 \"integer yresolution\" 16\n"
                        "LookAt 0 1 0  0 0 0.01  0 1 0\nCamera \"perspective\" \"float fov\" 20\nWorldBegin\n"
                        "LightSource \"infinite\" \"string filename\" \"" + file + "\"\n"
                        "Material \"diffuse\" \"rgb reflectance\" [0.5 0.5 0.5]\n"
                        "Shape \"trianglemesh\" \"point3 P\" [-1e4 0 -1e4 1e4 0 -1e4 1e4 0 1e4 -1e4 0 1e4] \"integer indices\" [0 1 2 0 2 3]\n";
    auto s = load_scene_from_string(scene, "env.pbrt");
    RenderOptions o;
    o.spp = 256;
    o.maxdepth = 1;
    RenderResult r = render(*s, o);
    double sum = 0.0, sum2 = 0.0;
    size_t n = size_t(r.image.width) * r.image.height;
    for (size_t i = 0; i < n; ++i) {
      sum += r.image.rgb[3 * i];
      sum2 += double(r.image.rgb[3 * i]) * r.image.rgb[3 * i];
    }
    double mean = sum / n, se = std::sqrt(std::max(0.0, sum2 / n - mean * mean) / n);
    double expected = 0.5 / kPi * irradiance_up(w, h, equal_area);
    EXPECT_NEAR(mean, expected, 4 * se + 0.003 * expected)
        << "a wrong light-sampling pdf shifts this mean by ~1.5% (checked by doubling it)" << (equal_area ? "equal-area" : "lat-long");
  }
}

}  // namespace
}  // namespace lantern
