// pbrt-v4's "ambientocclusion" integrator (Integrator::AmbientOcclusion)
// against closed forms. A floor under a parallel ceiling at height h, with
// occlusion counted within a distance m > h: a direction at angle theta
// from the normal reaches the ceiling after h / cos(theta), so it is open
// exactly when cos(theta) < h / m. Its cosine-weighted measure over the
// hemisphere, the value either sampling estimates, is (h / m)^2.
#include <gtest/gtest.h>

#include "lantern/render.h"
#include "lantern/scene.h"
#include "stat_compare.h"

namespace lantern {
namespace {

// The ceiling (z = 1) is an area light and the camera sits in a medium:
// ambient occlusion sees neither emission nor media, only surfaces.
std::string ceiling_scene(const std::string& integrator) {
  return R"(
MakeNamedMedium "fog" "string type" "homogeneous" "rgb sigma_a" [1 1 1] "rgb sigma_s" [1 1 1]
MediumInterface "" "fog"
LookAt 0 0 0.5  0 0 0  0 1 0
Camera "perspective" "float fov" 40
Film "rgb" "integer xresolution" 16 "integer yresolution" 16
Sampler "halton"
)" + integrator + R"(
WorldBegin
LightSource "infinite" "rgb L" [0.5 0.5 0.5]
Material "diffuse" "rgb reflectance" [0.2 0.4 0.6]
Shape "trianglemesh" "point3 P" [-20 -20 0  20 -20 0  20 20 0  -20 20 0] "integer indices" [0 1 2 0 2 3]
AttributeBegin
  AreaLightSource "diffuse" "rgb L" [5 5 5]
  Shape "trianglemesh" "point3 P" [-40 -40 1  -40 40 1  40 40 1  40 -40 1] "integer indices" [0 1 2 0 2 3]
AttributeEnd
)";
}

RegionStats occlusion_stats(const std::string& scene_text, bool spectral = false) {
  auto scene = load_scene_from_string(scene_text, "ao.pbrt", {});
  EXPECT_EQ(scene->settings.integrator, Integrator::AmbientOcclusion);
  RenderOptions o;
  o.integrator = scene->settings.integrator;
  o.spp = 64;
  o.spectral = spectral;
  return stats_of(render_runs(*scene, o, 4, 1), {{0, 0, 16, 16}});
}

void expect_white(const RegionStats& st, double expected, double allowance, const char* what) {
  for (size_t c = 0; c < 3; ++c)
    EXPECT_NEAR(st.mean[0][c], expected, 4.0 * st.std_error[0][c] + allowance) << what << ", channel " << c;
}

TEST(AmbientOcclusion, OpenFractionUnderACeilingIsTheClosedForm) {
  // h = 1, m = 2: (1/2)^2 of the cosine-weighted hemisphere is open.
  expect_white(occlusion_stats(ceiling_scene(R"(Integrator "ambientocclusion" "float maxdistance" 2)")), 0.25, 0.002,
               "cosine sampling");
  expect_white(occlusion_stats(ceiling_scene(R"(Integrator "ambientocclusion" "float maxdistance" 2 "bool cossample" false)")),
               0.25, 0.004, "uniform sampling");
  // m = 4: 1/16. With the default distance (infinite) the ceiling closes
  // all but what passes its edges, a fraction (1/40)^2-ish: about nothing.
  expect_white(occlusion_stats(ceiling_scene(R"(Integrator "ambientocclusion" "float maxdistance" 4)")), 0.0625, 0.002,
               "m = 4");
  expect_white(occlusion_stats(ceiling_scene(R"(Integrator "ambientocclusion")")), 0.0, 0.002, "no distance");
}

TEST(AmbientOcclusion, AnOpenFloorIsWhiteInRgbAndSpectral) {
  // No ceiling: every cosine-sampled direction is open, each sample exactly
  // 1 in RGB; sampled wavelengths of the illuminant average to white.
  const std::string open = R"(
LookAt 0 0 0.5  0 0 0  0 1 0
Camera "perspective" "float fov" 40
Film "rgb" "integer xresolution" 16 "integer yresolution" 16
Integrator "ambientocclusion" "integer maxdepth" 5
WorldBegin
Material "conductor"
Shape "trianglemesh" "point3 P" [-20 -20 0  20 -20 0  20 20 0  -20 20 0] "integer indices" [0 1 2 0 2 3]
)";
  const RegionStats rgb = occlusion_stats(open);
  for (size_t c = 0; c < 3; ++c) {
    EXPECT_NEAR(rgb.mean[0][c], 1.0, 1e-5) << "channel " << c;
    EXPECT_LT(rgb.std_error[0][c], 1e-6) << "channel " << c;
  }
  expect_white(occlusion_stats(open, true), 1.0, 0.01, "spectral");
}

TEST(AmbientOcclusion, ParametersAreChecked) {
  EXPECT_THROW(load_scene_from_string(ceiling_scene(R"(Integrator "ambientocclusion" "float maxdistance" 0)"), "ao.pbrt", {}),
               InputError);
  EXPECT_THROW(load_scene_from_string(ceiling_scene(R"(Integrator "ambientocclusion" "float maxdistance" -1)"), "ao.pbrt", {}),
               InputError);
}

}  // namespace
}  // namespace lantern
