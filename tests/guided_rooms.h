// The rooms the guiding tests render, and their options.
#pragma once

#include <memory>
#include <string>

#include "lantern/render.h"
#include "lantern/scene.h"

namespace lantern::guiding_test {

// A room (floor, walls, ceiling from `ceiling`) with diffuse, rough
// conductor and coated (layered, whose sampled density is not its pdf)
// surfaces, and `lights`.
inline std::shared_ptr<Scene> room(const std::string& ceiling, const std::string& lights, const std::string& name) {
  return load_scene_from_string(R"(
LookAt 0 1 -2.6  0 1 0  0 1 0
Camera "perspective" "float fov" [ 70 ]
Film "rgb" "integer xresolution" [ 32 ] "integer yresolution" [ 32 ]
WorldBegin
Material "diffuse" "rgb reflectance" [ 0.7 0.6 0.5 ]
Shape "trianglemesh" "point3 P" [ -2 0 -3  2 0 -3  2 0 2  -2 0 2 ] "integer indices" [ 0 1 2 0 2 3 ]
Shape "trianglemesh" "point3 P" [ -2 0 2  2 0 2  2 2 2  -2 2 2 ] "integer indices" [ 0 1 2 0 2 3 ]
Shape "trianglemesh" "point3 P" [ -2 0 -3  -2 2 -3  2 2 -3  2 0 -3 ] "integer indices" [ 0 1 2 0 2 3 ]
)" + ceiling + R"(
Material "conductor" "float roughness" [ 0.3 ]
Shape "trianglemesh" "point3 P" [ -2 0 -3  -2 0 2  -2 2 2  -2 2 -3 ] "integer indices" [ 0 1 2 0 2 3 ]
Material "coateddiffuse" "rgb reflectance" [ 0.2 0.5 0.8 ] "float roughness" [ 0.2 ]
Shape "trianglemesh" "point3 P" [ 2 0 -3  2 2 -3  2 2 2  2 0 2 ] "integer indices" [ 0 1 2 0 2 3 ]
)" + lights,
                                name);
}

// A closed room lit by a small light near the ceiling.
inline std::shared_ptr<Scene> guided_room() {
  return room(R"(Shape "trianglemesh" "point3 P" [ -2 2 -3  -2 2 2  2 2 2  2 2 -3 ] "integer indices" [ 0 1 2 0 2 3 ])",
              R"(AttributeBegin
  AreaLightSource "diffuse" "rgb L" [ 40 40 40 ]
  Translate 1.2 1.8 1.2
  Shape "sphere" "float radius" [ 0.08 ]
AttributeEnd)",
              "guided-room.pbrt");
}

// The same room lit only by a white sky through a hole in its ceiling:
// next-event estimation seldom draws a direction through the hole, BSDF
// sampling a few times more often, so what the eye subpaths gather comes
// from a narrow cone the guide learns (their MIS weights stay high there).
inline std::shared_ptr<Scene> skylit_room() {
  return room(R"(Shape "trianglemesh" "point3 P" [ -2 2 -3  -2 2 -0.9  2 2 -0.9  2 2 -3 ] "integer indices" [ 0 1 2 0 2 3 ]
Shape "trianglemesh" "point3 P" [ -2 2 -0.1  -2 2 2  2 2 2  2 2 -0.1 ] "integer indices" [ 0 1 2 0 2 3 ]
Shape "trianglemesh" "point3 P" [ -2 2 -0.9  -2 2 -0.1  -0.4 2 -0.1  -0.4 2 -0.9 ] "integer indices" [ 0 1 2 0 2 3 ]
Shape "trianglemesh" "point3 P" [ 0.4 2 -0.9  0.4 2 -0.1  2 2 -0.1  2 2 -0.9 ] "integer indices" [ 0 1 2 0 2 3 ])",
              R"(LightSource "infinite" "rgb L" [ 1 1 1 ])", "skylit-room.pbrt");
}

// The skylit room with a ball of fog under the hole: the light its
// scattering points gather comes through the hole, a narrow cone the
// guide's medium distributions learn.
inline std::shared_ptr<Scene> foggy_skylit_room() {
  return room(R"(Shape "trianglemesh" "point3 P" [ -2 2 -3  -2 2 -0.9  2 2 -0.9  2 2 -3 ] "integer indices" [ 0 1 2 0 2 3 ]
Shape "trianglemesh" "point3 P" [ -2 2 -0.1  -2 2 2  2 2 2  2 2 -0.1 ] "integer indices" [ 0 1 2 0 2 3 ]
Shape "trianglemesh" "point3 P" [ -2 2 -0.9  -2 2 -0.1  -0.4 2 -0.1  -0.4 2 -0.9 ] "integer indices" [ 0 1 2 0 2 3 ]
Shape "trianglemesh" "point3 P" [ 0.4 2 -0.9  0.4 2 -0.1  2 2 -0.1  2 2 -0.9 ] "integer indices" [ 0 1 2 0 2 3 ])",
              R"(LightSource "infinite" "rgb L" [ 1 1 1 ]
MakeNamedMedium "fog" "string type" "homogeneous"
  "rgb sigma_a" [ 0.1 0.2 0.3 ] "rgb sigma_s" [ 1.5 1.2 1.0 ] "float g" [ 0.4 ]
AttributeBegin
  MediumInterface "fog" ""
  Material "interface"
  Translate 0 0.9 -0.3
  Shape "sphere" "float radius" [ 0.75 ]
AttributeEnd)",
              "foggy-skylit-room.pbrt");
}

// (Guided to the end, --guide-stop never: these tests hold the guided
// estimator itself; tests/guide_stop_test.cpp holds where guiding stops.
// With the quadtree, which they were written for; tests/guiding_lobes_test.cpp
// holds the lobes.)
inline RenderOptions guided_options(bool guiding) {
  RenderOptions o;
  o.integrator = Integrator::Path;
  o.guiding = guiding;
  o.guide_stop = false;
  o.guide_distribution = GuideModel::Quadtree;
  o.spp = 64;
  o.maxdepth = 5;
  return o;
}

// bdpt at a light subpath rate (RenderOptions::light_subpath_rate).
inline RenderOptions bdpt_options(float light_subpath_rate) {
  RenderOptions o = guided_options(false);
  o.integrator = Integrator::Bdpt;
  o.light_subpath_rate = light_subpath_rate;
  return o;
}

}  // namespace lantern::guiding_test
