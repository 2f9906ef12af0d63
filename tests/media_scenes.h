// Scenes the media tests share.
#pragma once

#include <string>

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

}  // namespace lantern
