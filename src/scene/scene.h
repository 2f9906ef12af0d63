// The scene at run time: settings, the camera, and one dense pool per
// component kind. A pool that no entity uses is empty and costs nothing.
#pragma once

#include <memory>

#include "accel/embree_scene.h"
#include "camera/camera.h"
#include "film/pixel_filter.h"
#include "lantern/scene.h"
#include "light/lights.h"
#include "material/material.h"
#include "medium/medium.h"
#include "entity/shapes.h"
#include "texture/texture.h"

namespace lantern {

struct Scene {
  SceneSettings settings;
  CameraDesc camera;
  PixelFilter filter;
  ShapePools shapes;
  MaterialPools materials;
  TexturePools textures;
  LightPools lights;
  MediumPools media;
  std::unique_ptr<EmbreeScene> accel;
  Vec3 bounds_lo{0.f}, bounds_hi{0.f};
  size_t triangle_count = 0;            // unique: stored once each
  size_t prototype_triangle_count = 0;  // of those, the ones inside ObjectBegin/ObjectEnd
  size_t instanced_triangle_count = 0;  // each ObjectInstance counts its prototype's triangles

  // Whether anything moves while the shutter is open (motion blur).
  bool moving() const { return camera.motion != nullptr || !shapes.motions.empty(); }
};

}  // namespace lantern
