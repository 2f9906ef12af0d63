// pbrt-v3's "directlighting" integrator (Integrator::Direct): light straight
// from the lights at each vertex, paths continuing only through specular
// scattering. On a scene without specular surfaces it is the path tracer
// at maxdepth 1; through a mirror it is a closed form.
#include <gtest/gtest.h>

#include "lantern/render.h"
#include "lantern/scene.h"
#include "stat_compare.h"

namespace lantern {
namespace {

// A diffuse floor and sphere under a sky and a disk light: no specular
// surface, and light that bounces (the floor lights the sphere).
const char* kDiffuse = R"(
LookAt 0 -4 2  0 0 0.6  0 0 1
Camera "perspective" "float fov" 40
Film "rgb" "integer xresolution" 32 "integer yresolution" 24
Sampler "halton"
WorldBegin
LightSource "infinite" "rgb L" [0.3 0.35 0.4]
AttributeBegin
  AreaLightSource "diffuse" "rgb L" [6 5 4]
  Translate 0 0 3
  ReverseOrientation
  Shape "disk" "float radius" 0.5
AttributeEnd
Material "diffuse" "rgb reflectance" [0.7 0.2 0.1]
AttributeBegin
  Translate 0 0 0.7
  Shape "sphere" "float radius" 0.7
AttributeEnd
Material "diffuse" "rgb reflectance" [0.6 0.6 0.6]
Shape "trianglemesh" "point3 P" [-4 -4 0  4 -4 0  4 4 0  -4 4 0] "integer indices" [0 1 2 0 2 3]
)";

TEST(DirectLighting, IsThePathTracerAtDepthOneWithoutSpecularSurfaces) {
  auto scene = load_scene_from_string(kDiffuse, "diffuse.pbrt", {});
  const std::vector<Region> regions = {{0, 0, 16, 12}, {16, 0, 16, 12}, {0, 12, 16, 12}, {16, 12, 16, 12}, {12, 8, 8, 8}};
  RenderOptions o;
  o.spp = 64;
  o.maxdepth = 5;
  o.integrator = Integrator::Direct;
  const RegionStats direct = stats_of(render_runs(*scene, o, 6, 1), regions);
  o.integrator = Integrator::Path;
  o.maxdepth = 1;
  const RegionStats path1 = stats_of(render_runs(*scene, o, 6, 21), regions);
  expect_means_agree(path1, direct, 0.005, "directlighting against path at maxdepth 1");
  // ... and not the path tracer at depth 5, whose bounced light brightens
  // the sphere's lower half (region 4): the comparison can fail.
  o.maxdepth = 5;
  const RegionStats path5 = stats_of(render_runs(*scene, o, 6, 41), regions);
  EXPECT_GT(path5.mean[4][0], direct.mean[4][0] * 1.05) << "no indirect light in the path tracer's sphere?";
}

// A diffuse floor (albedo 0.5) under a light straight down (irradiance 1)
// seen directly and in a vertical copper mirror: every camera path ends on
// the floor, after the mirror's Fresnel reflectance F or none, so each
// pixel is 0.5 / pi times what it is when the floor is gone and the sky
// (radiance 1) is seen instead, F or 1, sample for sample.
std::string mirror_scene(bool floor) {
  std::string s = R"(
LookAt -2 0 3  3 0 0.5  0 0 1
Camera "perspective" "float fov" 30
Film "rgb" "integer xresolution" 24 "integer yresolution" 16
Sampler "halton"
WorldBegin
)";
  s += floor ? "LightSource \"distant\" \"point3 from\" [0 0 1] \"point3 to\" [0 0 0] \"rgb L\" [1 1 1]\n"
             : "LightSource \"infinite\" \"rgb L\" [1 1 1]\n";
  s += R"(Material "conductor" "float roughness" 0
Shape "trianglemesh" "point3 P" [3 -6 0  3 6 0  3 6 8  3 -6 8] "integer indices" [0 1 2 0 2 3]
)";
  if (floor)
    s += "Material \"diffuse\" \"rgb reflectance\" [0.5 0.5 0.5]\n"
         "Shape \"trianglemesh\" \"point3 P\" [-60 -60 0  10 -60 0  10 60 0  -60 60 0] \"integer indices\" [0 1 2 0 2 3]\n";
  return s;
}

TEST(DirectLighting, FollowsSpecularChainsToTheLightedSurface) {
  auto lit = load_scene_from_string(mirror_scene(true), "floor.pbrt", {});
  auto sky = load_scene_from_string(mirror_scene(false), "sky.pbrt", {});
  RenderOptions o;
  o.spp = 4;
  o.integrator = Integrator::Direct;
  const Image a = render(*lit, o).image, b = render(*sky, o).image;
  ASSERT_EQ(a.rgb.size(), b.rgb.size());
  size_t mirrored = 0;
  for (size_t i = 0; i < a.rgb.size(); ++i) {
    EXPECT_NEAR(a.rgb[i], 0.5f / kPi * b.rgb[i], 2e-5f * b.rgb[i] + 1e-7f) << "value " << i;
    if (b.rgb[i] < 0.99f) ++mirrored;
  }
  EXPECT_GT(mirrored, a.rgb.size() / 4);  // the mirror fills a good part of the view
  // The path tracer at maxdepth 1 stops at the floor behind the mirror:
  // black where the mirror fills the pixel (all but the pixels along its
  // edge with the floor, which see some floor directly: a row or two).
  o.integrator = Integrator::Path;
  o.maxdepth = 1;
  const Image p = render(*lit, o).image;
  size_t dark = 0;
  for (size_t i = 0; i < p.rgb.size(); ++i) dark += b.rgb[i] < 0.99f && p.rgb[i] == 0.f;
  EXPECT_GT(dark, mirrored * 3 / 4) << "of " << mirrored;
}

TEST(DirectLighting, IsNamedAsPbrtV3NamesIt) {
  auto s = load_scene_from_string("Integrator \"directlighting\" \"string strategy\" \"one\" \"integer maxdepth\" 3\n"
                                  "WorldBegin\n",
                                  "d.pbrt", {});
  EXPECT_EQ(scene_settings(*s).integrator, Integrator::Direct);
  EXPECT_EQ(scene_settings(*s).maxdepth, 3);
  EXPECT_EQ(std::string(name(Integrator::Direct)), "directlighting");
  EXPECT_THROW(load_scene_from_string("Integrator \"directlighting\" \"string strategy\" \"some\"\nWorldBegin\n", "e.pbrt",
                                      {}),
               InputError);
}

}  // namespace
}  // namespace lantern
