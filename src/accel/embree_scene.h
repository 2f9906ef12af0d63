// The Embree device and the scene built from the geometry pools. Geometry ID
// i in Embree is entry i of ShapePools::geometries.
#pragma once

#include <embree3/rtcore.h>

#include <mutex>
#include <string>

#include "scene/shapes.h"

namespace lantern {

class EmbreeScene {
 public:
  explicit EmbreeScene(const ShapePools& shapes);  // throws std::runtime_error
  ~EmbreeScene();
  EmbreeScene(const EmbreeScene&) = delete;
  EmbreeScene& operator=(const EmbreeScene&) = delete;

  RTCScene handle() const { return scene_; }
  // Bounds of everything in the scene.
  void bounds(Vec3* lo, Vec3* hi) const;

 private:
  static void on_error(void* user, RTCError code, const char* str);
  void check(const char* what);

  std::mutex error_mutex_;
  std::string error_;
  RTCDevice device_ = nullptr;
  RTCScene scene_ = nullptr;
};

}  // namespace lantern
