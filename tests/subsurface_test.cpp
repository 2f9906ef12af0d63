// pbrt's "subsurface" and pbrt-v3's "kdsubsurface": a dielectric boundary
// around a homogeneous medium (scene/builder_subsurface.cpp), traced as a
// random walk by every integrator. Energy is conserved where nothing
// absorbs, the integrators agree, and each way of giving the coefficients
// is read with pbrt-v4's rules.
#include <gtest/gtest.h>

#include "expect_error.h"
#include "lantern/render.h"
#include "lantern/scene.h"
#include "scene/scene.h"
#include "stat_compare.h"

namespace lantern {
namespace {

RenderOptions render_options(const char* integrator, int spp, int maxdepth) {
  RenderOptions o;
  o.integrator = parse_integrator(integrator);
  o.spp = spp;
  o.maxdepth = maxdepth;
  return o;
}

// A sphere that scatters and does not absorb, under a white sky of
// radiance 1 and nothing else: all light that enters leaves, so every
// pixel of it is 1 (a white furnace), however often it scatters or is
// reflected inside the boundary.
TEST(Subsurface, NonAbsorbingSphereInAWhiteFurnaceStaysAtOne) {
  const char* text = R"(
LookAt 0 0 4  0 0 0  0 1 0
Camera "perspective" "float fov" 20
Film "rgb" "integer xresolution" 12 "integer yresolution" 12
WorldBegin
LightSource "infinite" "rgb L" [1 1 1]
Material "subsurface" "rgb sigma_a" [0 0 0] "rgb sigma_s" [0.5 1 2] "float eta" 1.33 "float g" 0.3
Shape "sphere" "float radius" 1
)";
  auto scene = load_scene_from_string(text, "furnace.pbrt", {});
  ASSERT_EQ(scene->media.homogeneous.size(), 1u);
  // 16 samples a pixel even in the sanitizer suite (render_runs would cut
  // them to 4): with a few hundred samples, the many-bounce tail of the
  // walks is too rarely drawn for the standard error to see it.
  for (const char* integrator : {"path", "bdpt"}) {
    std::vector<Image> runs;
    for (uint64_t seed = 1; seed <= 4; ++seed) {
      RenderOptions o = render_options(integrator, 16, 400);
      o.seed = seed;
      runs.push_back(render(*scene, o).image);
    }
    const RegionStats st = stats_of(runs, {{3, 3, 6, 6}});
    for (size_t c = 0; c < 3; ++c)
      EXPECT_NEAR(st.mean[0][c], 1.0, 4.0 * st.std_error[0][c] + 0.01) << integrator << ", channel " << c;
  }
  // The interior is there: absorbing, the same sphere is darker (a glass
  // ball would stay at 1).
  std::string absorbing = text;
  absorbing.replace(absorbing.find("[0 0 0]"), 7, "[1 1 1]");
  const RegionStats dark = stats_of(render_runs(*load_scene_from_string(absorbing, "a.pbrt", {}),
                                                render_options("path", 16, 400), 2, 1),
                                    {{3, 3, 6, 6}});
  for (size_t c = 0; c < 3; ++c) EXPECT_LT(dark.mean[0][c], 0.8) << "channel " << c;
}

// A reflectance means what a thick slab of the medium gives back of the
// light entering it (material/subsurface_albedo.h): seen straight on under
// a white sky, a flat expanse of it (a sphere of radius 100 from 1 away)
// is that reflectance, plus the boundary's specular reflection of the sky
// (0.02 at normal incidence for eta 1.33) and what the exit's angular
// spread moves (measured within 0.01 at these three values).
TEST(Subsurface, ReflectanceIsWhatAThickSlabGivesBack) {
  for (const float R : {0.2f, 0.5f, 0.8f}) {
    const std::string text = R"(
LookAt 0 0 101  0 0 0  0 1 0
Camera "perspective" "float fov" 5
Film "rgb" "integer xresolution" 4 "integer yresolution" 4
WorldBegin
LightSource "infinite" "rgb L" [1 1 1]
Material "subsurface" "float mfp" 0.1 "rgb reflectance" [)" + std::to_string(R) + " " + std::to_string(R) + " " +
                             std::to_string(R) + R"(]
Shape "sphere" "float radius" 100
)";
    auto scene = load_scene_from_string(text, "slab.pbrt", {});
    const RegionStats st = stats_of(render_runs(*scene, render_options("path", 256, 1000), 4, 1), {{0, 0, 4, 4}});
    for (size_t c = 0; c < 3; ++c)
      EXPECT_NEAR(st.mean[0][c], R + 0.01, 4.0 * st.std_error[0][c] + 0.02) << "reflectance " << R << ", channel " << c;
  }
}

// A coloured, absorbing sphere given by reflectance and mean free path on
// a floor under a small light: path, bdpt and vcm see the same image
// (region means), through the boundary both ways. (Light tracing alone
// cannot: its camera connections from inside end on the boundary, as they
// do behind any glass.)
TEST(Subsurface, IntegratorsAgree) {
  const char* text = R"(
LookAt 0 -3 1.6  0 0 0.5  0 0 1
Camera "perspective" "float fov" 36
Film "rgb" "integer xresolution" 24 "integer yresolution" 16
Sampler "independent"
WorldBegin
AttributeBegin
  AreaLightSource "diffuse" "rgb L" [12 12 12]
  Translate 0.5 -0.5 2.5
  ReverseOrientation
  Shape "disk" "float radius" 0.4
AttributeEnd
Material "diffuse" "rgb reflectance" [0.5 0.5 0.5]
Shape "trianglemesh" "point3 P" [-5 -5 0  5 -5 0  5 5 0  -5 5 0] "integer indices" [0 1 2 0 2 3]
AttributeBegin
  Translate 0 0 0.5
  Material "subsurface" "rgb reflectance" [0.8 0.45 0.2] "float mfp" 0.2 "float eta" 1.4
  Shape "sphere" "float radius" 0.5
AttributeEnd
)";
  auto scene = load_scene_from_string(text, "sss.pbrt", {});
  const std::vector<Region> regions = {{8, 4, 8, 8}, {0, 10, 24, 6}, {10, 6, 4, 4}};
  const RegionStats path = stats_of(render_runs(*scene, render_options("path", 32, 64), 6, 1), regions);
  for (const char* integrator : {"bdpt", "vcm"}) {
    const RegionStats other = stats_of(render_runs(*scene, render_options(integrator, 32, 64), 6, 101), regions);
    expect_means_agree(path, other, 0.03, integrator);
  }
}

TEST(Subsurface, CoefficientsAreReadAsPbrtV4ReadsThem) {
  auto material = [](const std::string& params) {
    return load_scene_from_string("WorldBegin\nMaterial " + params + "\nShape \"sphere\"\n", "m.pbrt", {});
  };
  // Defaults (per mm, as pbrt-v4's) times scale.
  auto s = material("\"subsurface\" \"float scale\" 2");
  ASSERT_EQ(s->media.homogeneous.size(), 1u);
  EXPECT_FLOAT_EQ(s->media.homogeneous[0].sigma_s[0], 2.f * 2.55f);
  EXPECT_FLOAT_EQ(s->media.homogeneous[0].sigma_a[2], 2.f * 0.014f);
  EXPECT_EQ(s->shapes.geometries[0].media.inside, MediumHandle::make(MediumKind::Homogeneous, 0));
  EXPECT_FLOAT_EQ(s->materials.dielectric[0].eta.value, 1.33f);
  // A named measured medium; g is then 0.
  s = material("\"subsurface\" \"string name\" \"Ketchup\" \"float g\" 0.5");
  EXPECT_EQ(s->media.homogeneous[0].g, 0.f);
  EXPECT_GT(s->media.homogeneous[0].sigma_a[1], s->media.homogeneous[0].sigma_a[0]);
  // Reflectance and mean free path: sigma_t = 1 / mfp, the albedo brighter
  // for a brighter reflectance; pbrt-v3's kdsubsurface reads Kd.
  s = material("\"subsurface\" \"rgb reflectance\" [0.2 0.5 0.9] \"float mfp\" 0.5");
  const HomogeneousMedium m = s->media.homogeneous[0];  // a copy: s is replaced below
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(m.sigma_a[c] + m.sigma_s[c], 2.f, 1e-5f) << c;
  EXPECT_LT(m.sigma_s[0], m.sigma_s[1]);
  EXPECT_LT(m.sigma_s[1], m.sigma_s[2]);
  s = material("\"kdsubsurface\" \"rgb Kd\" [0.2 0.5 0.9] \"float mfp\" 0.5");
  EXPECT_FLOAT_EQ(s->media.homogeneous[0].sigma_s[1], m.sigma_s[1]);
  expect_load_error("WorldBegin\nMaterial \"subsurface\" \"rgb sigma_a\" [1 1 1]\n", "a.pbrt", {"a.pbrt:2", "together"});
  expect_load_error("WorldBegin\nTexture \"t\" \"spectrum\" \"constant\" \"rgb value\" [1 1 1]\n"
                    "Material \"subsurface\" \"texture reflectance\" \"t\"\n",
                    "t.pbrt", {"t.pbrt:3", "textured subsurface coefficient"});
  expect_load_error("WorldBegin\nMaterial \"subsurface\" \"string name\" \"Ketchupp\"\n", "n.pbrt", {"Ketchupp", "Ketchup"});
  expect_load_error("WorldBegin\nMakeNamedMaterial \"s\" \"string type\" \"subsurface\"\n"
                    "MakeNamedMaterial \"d\" \"string type\" \"diffuse\"\n"
                    "Material \"mix\" \"string materials\" [\"s\" \"d\"]\n",
                    "x.pbrt", {"x.pbrt:4", "cannot be mixed"});
}

}  // namespace
}  // namespace lantern
