// The mix material: amount 0 and 1 render each material exactly, 0.3 renders
// the 0.7 / 0.3 blend of their images (path and bdpt, statistically); a
// textured amount selects per point. The interface material is invisible.
#include <gtest/gtest.h>

#include "expect_error.h"
#include "stat_compare.h"

namespace lantern {
namespace {

// A sphere under a small light and a sky, on a floor, with material `m`.
std::shared_ptr<Scene> mix_scene_with(const std::string& m) {
  return load_scene_from_string(R"(
LookAt 0 2 -4  0 0.5 0  0 1 0
Camera "perspective" "float fov" [ 35 ]
Film "rgb" "integer xresolution" [ 16 ] "integer yresolution" [ 16 ]
WorldBegin
LightSource "infinite" "rgb L" [ 0.3 0.3 0.35 ]
AttributeBegin
  AreaLightSource "diffuse" "rgb L" [ 20 20 20 ]
  Translate 1 3 -1
  Shape "sphere" "float radius" [ 0.2 ]
AttributeEnd
MakeNamedMaterial "red" "string type" "diffuse" "rgb reflectance" [ 0.8 0.1 0.1 ]
MakeNamedMaterial "gold" "string type" "conductor" "spectrum eta" "metal-Au-eta" "spectrum k" "metal-Au-k"
  "float roughness" [ 0.2 ]
Material "diffuse" "rgb reflectance" [ 0.5 0.5 0.5 ]
Shape "trianglemesh" "point3 P" [ -5 0 -5  5 0 -5  5 0 5  -5 0 5 ] "integer indices" [ 0 1 2  0 2 3 ]
)" + m + "\nTranslate 0 0.8 0\nShape \"sphere\" \"float radius\" [ 0.8 ]\n",
                                "mix.pbrt");
}

std::string mix_of(const char* amount) {
  return std::string("Material \"mix\" \"string materials\" [ \"red\" \"gold\" ] ") + amount;
}

TEST(MixMaterial, AmountZeroAndOneAreEachMaterial) {
  expect_identical_renders(*mix_scene_with(mix_of("\"float amount\" 0")), *mix_scene_with("NamedMaterial \"red\""),
                           {"path", "bdpt"});
  expect_identical_renders(*mix_scene_with(mix_of("\"float amount\" 1")), *mix_scene_with("NamedMaterial \"gold\""),
                           {"path", "bdpt"});
}

TEST(MixMaterial, AmountBlendsTheImages) {
  const std::vector<Region> regions = {{0, 0, 16, 16}, {4, 4, 8, 8}, {6, 2, 4, 4}};
  for (const char* integrator : {"path", "bdpt"}) {
    RenderOptions o;
    o.integrator = parse_integrator(integrator);
    o.spp = 16;
    auto red = render_runs(*mix_scene_with("NamedMaterial \"red\""), o, 10, 500);
    auto gold = render_runs(*mix_scene_with("NamedMaterial \"gold\""), o, 10, 600);
    auto mixed = render_runs(*mix_scene_with(mix_of("\"float amount\" 0.3")), o, 10, 700);
    std::vector<Image> blend = red;
    for (size_t r = 0; r < blend.size(); ++r)
      for (size_t k = 0; k < blend[r].rgb.size(); ++k) blend[r].rgb[k] = 0.7f * red[r].rgb[k] + 0.3f * gold[r].rgb[k];
    SCOPED_TRACE(integrator);
    EXPECT_LT(max_z(stats_of(mixed, regions), stats_of(blend, regions)), 4.5);
  }
}

// (Without an infinite light, whose power follows the scene's bounds and
// with it the light selection's random choices.)
TEST(MixMaterial, InterfaceIsInvisible) {
  const std::string head = R"(
LookAt 0 2 -4  0 0.5 0  0 1 0
Camera "perspective" "float fov" [ 35 ]
Film "rgb" "integer xresolution" [ 16 ] "integer yresolution" [ 16 ]
WorldBegin
AttributeBegin
  AreaLightSource "diffuse" "rgb L" [ 20 20 20 ]
  Translate 1 3 -1
  Shape "sphere" "float radius" [ 0.2 ]
AttributeEnd
Material "diffuse" "rgb reflectance" [ 0.5 0.5 0.5 ]
Shape "trianglemesh" "point3 P" [ -5 0 -5  5 0 -5  5 0 5  -5 0 5 ] "integer indices" [ 0 1 2  0 2 3 ]
)";
  const std::string sphere = "Material \"diffuse\" \"rgb reflectance\" [ 0.8 0.1 0.1 ]\nTranslate 0 0.8 0\nShape \"sphere\" \"float radius\" [ 0.8 ]\n";
  auto plain = load_scene_from_string(head + sphere, "plain.pbrt");
  auto with_interface = load_scene_from_string(
      head + "AttributeBegin\nMaterial \"interface\"\nShape \"sphere\" \"float radius\" [ 3 ]\nAttributeEnd\n" + sphere,
      "interface.pbrt");
  expect_identical_renders(*plain, *with_interface, {"path", "bdpt", "lt"});
}

TEST(MixMaterial, MisuseIsAClearError) {
  expect_load_error("WorldBegin\nMaterial \"mix\" \"string materials\" [ \"red\" ]\n", "mix.pbrt",
                    {"mix.pbrt:2", "two materials"});
  expect_load_error("WorldBegin\nMakeNamedMaterial \"red\" \"string type\" \"diffuse\"\n"
                    "Material \"mix\" \"string materials\" [ \"red\" \"nope\" ]\n",
                    "mix.pbrt", {"mix.pbrt:3", "no material named \"nope\""});
}

}  // namespace
}  // namespace lantern
