// Scenes and checks the media tests share.
#pragma once

#include <string>
#include <vector>

#include <random>

#include "light/volume_light.h"
#include "scene/scene.h"
#include "stat_compare.h"

namespace lantern {

// A slab between z = 1 and z = 3 (two "interface" planes, normals
// outwards) of the medium "slab", which make_medium defines, between the
// camera (10-degree field of view, box filter) and an emitter of radiance
// 1 that fills the view.
inline std::string slab_scene(const std::string& make_medium) {
  return R"(
PixelFilter "box"
LookAt 0 0 0  0 0 1  0 1 0
Camera "perspective" "float fov" [ 10 ]
WorldBegin
)" + make_medium + R"(
AttributeBegin
  MediumInterface "slab" ""
  Material "interface"
  Shape "trianglemesh" "point3 P" [ -10 -10 1  -10 10 1  10 10 1  10 -10 1 ] "integer indices" [ 0 1 2 0 2 3 ]
  Shape "trianglemesh" "point3 P" [ -10 -10 3  10 -10 3  10 10 3  -10 10 3 ] "integer indices" [ 0 1 2 0 2 3 ]
AttributeEnd
AttributeBegin
  AreaLightSource "diffuse" "rgb L" [ 1 1 1 ]
  Shape "trianglemesh" "point3 P" [ -10 -10 5  -10 10 5  10 10 5  10 -10 5 ] "integer indices" [ 0 1 2 0 2 3 ]
AttributeEnd
)";
}

// A medium scene's standard checks at 40x30: path and bdpt (32 spp) and
// lt (64 spp) agree on the regions' means over 8 runs; and, at 32x24,
// 2 spp, maxdepth 6, 1 and 2 threads give the same bits.
inline void expect_medium_integrators_agree(const Scene& scene, const std::vector<Region>& regions) {
  const RegionStats path = render_stats(scene, "path", 40, 30, 32, 8, regions);
  const RegionStats bdpt = render_stats(scene, "bdpt", 40, 30, 32, 8, regions);
  const RegionStats lt = render_stats(scene, "lt", 40, 30, 64, 8, regions);
  EXPECT_LT(max_z(path, bdpt), 4.5);
  EXPECT_LT(max_z(bdpt, lt), 4.5);
}

inline void expect_medium_thread_invariant(const Scene& scene) {
  RenderOptions o;
  o.width = 32;
  o.height = 24;
  o.spp = 2;
  o.maxdepth = 6;
  expect_thread_invariant(scene, o, {"path", "bdpt", "lt"});
}

// A volume light's points, weighted by their density, integrate sigma_a Le
// over the medium: against a midpoint sum over the light's box, for the
// glowing fog's ember (a uniformgrid) and the burning NanoVDB blob.
inline void expect_volume_light_integrates(const Scene& scene) {
  ASSERT_FALSE(scene.lights.volume.empty());
  for (const VolumeLight& v : scene.lights.volume) {
    auto f = [&](const Vec3& p) {
      Spectrum a, s;
      scene.media.coefficients_at(v.medium, p, SampledWavelengths::rgb(), &a, &s);
      return a * scene.media.Le(v.medium, p, SampledWavelengths::rgb());
    };
    const int n = 96;
    double brute[3] = {0, 0, 0};
    for (int z = 0; z < n; ++z)
      for (int y = 0; y < n; ++y)
        for (int x = 0; x < n; ++x) {
          const Vec3 u = (Vec3(float(x), float(y), float(z)) + 0.5f) / float(n);
          const Spectrum e = f(Vec3(v.render_from_unit * Vec4(u, 1.f)));
          for (int c = 0; c < 3; ++c) brute[c] += double(e[c]) * double(v.volume) / double(n * n * n);
        }
    std::mt19937 rng(3);
    std::uniform_real_distribution<float> uni(0.f, 1.f);
    const int samples = 200000;
    double sum[3] = {0, 0, 0}, sum2[3] = {0, 0, 0};
    for (int i = 0; i < samples; ++i) {
      float pdf;
      const Vec3 p = sample_volume_point(v, Vec3(uni(rng), uni(rng), uni(rng)), &pdf);
      ASSERT_GT(pdf, 0.f);
      EXPECT_NEAR(volume_point_density(v, p), pdf, 1e-3f * pdf);
      const Spectrum e = f(p) / pdf;
      for (int c = 0; c < 3; ++c) sum[c] += e[c], sum2[c] += double(e[c]) * e[c];
    }
    for (int c = 0; c < 3; ++c) {
      const double mean = sum[c] / samples, se = std::sqrt(std::max(0.0, sum2[c] / samples - mean * mean) / samples);
      EXPECT_LT(std::fabs(mean - brute[c]), 4.5 * se + 0.01 * std::fabs(brute[c])) << "channel " << c << ": " << mean << " against " << brute[c];
    }
  }
}

}  // namespace lantern
