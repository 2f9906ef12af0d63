// pbrt's perspective camera: a pinhole or a thin lens, looking down +z in a
// left-handed camera space; raster x grows with camera x, raster y downwards.
#pragma once

#include "math/common.h"
#include "math/sampling.h"

namespace lantern {

struct CameraDesc {
  Mat4 world_from_camera{1.f};
  float fov_degrees = 90.f;
  float lens_radius = 0.f;
  float focal_distance = 1e6f;
  bool has_screen_window = false;
  float screen_window[4] = {-1.f, 1.f, -1.f, 1.f};  // xmin xmax ymin ymax
};

struct CameraRay {
  Vec3 o, d;  // d is unit length
};

class PerspectiveCamera {
 public:
  PerspectiveCamera() = default;
  PerspectiveCamera(const CameraDesc& desc, int width, int height);

  // p_raster in [0, width) x [0, height).
  CameraRay generate_ray(Vec2 p_raster, Vec2 u_lens) const;
  int width() const { return width_; }
  int height() const { return height_; }
  Vec3 position() const { return Vec3(world_from_camera_[3]); }

 private:
  Mat4 world_from_camera_{1.f};
  int width_ = 1, height_ = 1;
  float sx0_ = -1, sx1_ = 1, sy0_ = -1, sy1_ = 1;
  float tan_half_ = 1.f;
  float lens_radius_ = 0.f, focal_distance_ = 1e6f;
};

}  // namespace lantern
