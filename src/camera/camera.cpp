#include "camera/camera.h"

namespace lantern {

PerspectiveCamera::PerspectiveCamera(const CameraDesc& d, int width, int height)
    : world_from_camera_(d.world_from_camera), width_(width), height_(height) {
  float aspect = float(width) / float(height);
  if (d.has_screen_window) {
    sx0_ = d.screen_window[0];
    sx1_ = d.screen_window[1];
    sy0_ = d.screen_window[2];
    sy1_ = d.screen_window[3];
  } else if (aspect > 1.f) {
    sx0_ = -aspect;
    sx1_ = aspect;
  } else {
    sy0_ = -1.f / aspect;
    sy1_ = 1.f / aspect;
  }
  tan_half_ = std::tan(glm::radians(d.fov_degrees) * 0.5f);
  lens_radius_ = d.lens_radius;
  focal_distance_ = d.focal_distance;
}

CameraRay PerspectiveCamera::generate_ray(Vec2 p, Vec2 u_lens) const {
  float sx = sx0_ + (p.x / float(width_)) * (sx1_ - sx0_);
  float sy = sy1_ - (p.y / float(height_)) * (sy1_ - sy0_);
  Vec3 dir = glm::normalize(Vec3(sx * tan_half_, sy * tan_half_, 1.f));
  Vec3 origin(0.f);
  if (lens_radius_ > 0.f) {
    Vec2 lens = lens_radius_ * sample_uniform_disk_concentric(u_lens);
    Vec3 focus = dir * (focal_distance_ / dir.z);
    origin = Vec3(lens.x, lens.y, 0.f);
    dir = glm::normalize(focus - origin);
  }
  CameraRay r;
  r.o = Vec3(world_from_camera_ * Vec4(origin, 1.f));
  r.d = glm::normalize(Vec3(world_from_camera_ * Vec4(dir, 0.f)));
  return r;
}

}  // namespace lantern
