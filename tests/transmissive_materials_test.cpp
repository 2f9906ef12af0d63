// diffusetransmission and thindielectric in whole scenes: path, bdpt and
// light tracing agree where light reaches the floor only through them
// (transmission in both transport directions, MIS densities across a
// transmitting diffuse vertex and a specular one).
#include <gtest/gtest.h>

#include "sanitizer.h"
#include "stat_compare.h"

namespace lantern {
namespace {

TEST(TransmissiveMaterials, IntegratorsAgreeThroughDiffuseTransmissionAndThinGlass) {
  if (LANTERN_ASAN) GTEST_SKIP() << "the Release suite runs it; bsdf_test covers both BSDFs under the sanitizers";
  auto scene = load_scene_from_string(R"(
LookAt 0 0.4 -3.2  0 0.7 0  0 1 0
Camera "perspective" "float fov" [ 40 ]
Film "rgb" "integer xresolution" [ 24 ] "integer yresolution" [ 24 ]
WorldBegin
AttributeBegin
  AreaLightSource "diffuse" "rgb L" [ 6 6 6 ]
  Shape "trianglemesh" "point3 P" [ -0.5 2 -0.5  0.5 2 -0.5  0.5 2 0.5  -0.5 2 0.5 ] "integer indices" [ 0 1 2 0 2 3 ]
AttributeEnd
Material "diffuse" "rgb reflectance" [ 0.5 0.5 0.5 ]
Shape "trianglemesh" "point3 P" [ -20 0 -20 20 0 -20 20 0 20 -20 0 20 ] "integer indices" [ 0 1 2 0 2 3 ]
# A lamp shade under the light's left half, a thin pane under its right;
# the camera sees their undersides and the floor.
AttributeBegin
  Material "diffusetransmission" "rgb reflectance" [ 0.1 0.15 0.05 ] "rgb transmittance" [ 0.8 0.5 0.7 ]
  Shape "trianglemesh" "point3 P" [ -1.5 1.2 -1.5  0 1.2 -1.5  0 1.5 1.5  -1.5 1.5 1.5 ] "integer indices" [ 0 1 2 0 2 3 ]
AttributeEnd
AttributeBegin
  Material "thindielectric" "float eta" [ 1.8 ]
  Shape "trianglemesh" "point3 P" [ 0 1.0 -1.5  1.5 1.3 -1.5  1.5 1.3 1.5  0 1.0 1.5 ] "integer indices" [ 0 1 2 0 2 3 ]
AttributeEnd
)",
                                      "transmissive.pbrt");
  // The shade's underside and the pane (top), the floor under each (bottom).
  const std::vector<Region> regions = {{0, 0, 24, 24}, {0, 0, 12, 8}, {12, 0, 12, 8}, {0, 16, 12, 8}, {12, 16, 12, 8}};
  auto path = render_stats(*scene, "path", 24, 24, 64, 16, regions);
  auto bdpt = render_stats(*scene, "bdpt", 24, 24, 16, 16, regions);
  auto lt = render_stats(*scene, "lt", 24, 24, 32, 16, regions);
  EXPECT_LT(max_z(bdpt, path), 5.0);
  EXPECT_LT(max_z(lt, path), 5.0);
}

}  // namespace
}  // namespace lantern
