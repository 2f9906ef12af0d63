// Scenes and checks the media tests share.
#pragma once

#include <string>
#include <vector>

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

}  // namespace lantern
