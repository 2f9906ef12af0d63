#include "camera/camera.h"

namespace lantern {

PerspectiveCamera::PerspectiveCamera(const CameraDesc& d, int width, int height, Vec2 film_margin)
    : world_from_camera_(d.world_from_camera), width_(width), height_(height), margin_(film_margin) {
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
  camera_from_world_ = glm::inverse(world_from_camera_);
  forward_ = glm::normalize(Vec3(world_from_camera_ * Vec4(0.f, 0.f, 1.f, 0.f)));
  film_area_ = (sx1_ - sx0_) * (sy1_ - sy0_) * tan_half_ * tan_half_;
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

float PerspectiveCamera::We(const Vec3& p_lens, const Vec3& d, Vec2* p_raster) const {
  float cos_t = cos_theta(d);
  if (cos_t <= 0.f) return 0.f;
  // Where the ray crosses the plane of focus, seen from the lens centre,
  // gives the film position (for a pinhole, the direction itself does).
  Vec3 o = Vec3(camera_from_world_ * Vec4(p_lens, 1.f));
  Vec3 dc = Vec3(camera_from_world_ * Vec4(d, 0.f));
  Vec3 q = lens_radius_ > 0.f ? o + dc * (focal_distance_ / dc.z) : dc;
  float sx = q.x / q.z / tan_half_, sy = q.y / q.z / tan_half_;
  Vec2 r((sx - sx0_) / (sx1_ - sx0_) * float(width_), (sy1_ - sy) / (sy1_ - sy0_) * float(height_));
  if (!(r.x > -margin_.x && r.x < float(width_) + margin_.x && r.y > -margin_.y && r.y < float(height_) + margin_.y))
    return 0.f;
  *p_raster = r;
  float cos2 = cos_t * cos_t;
  return 1.f / (film_area_ * lens_area() * cos2 * cos2);
}

float PerspectiveCamera::pdf_dir(const Vec3& d) const {
  float cos_t = cos_theta(d);
  return cos_t > 0.f ? 1.f / (film_area_ * cos_t * cos_t * cos_t) : 0.f;
}

std::optional<CameraSample> PerspectiveCamera::sample_wi(const Vec3& ref, Vec2 u_lens) const {
  Vec3 p_lens_cam(0.f);
  if (lens_radius_ > 0.f) {
    Vec2 l = lens_radius_ * sample_uniform_disk_concentric(u_lens);
    p_lens_cam = Vec3(l.x, l.y, 0.f);
  }
  CameraSample cs;
  cs.p_lens = Vec3(world_from_camera_ * Vec4(p_lens_cam, 1.f));
  Vec3 d = cs.p_lens - ref;
  float dist2 = glm::dot(d, d);
  if (!(dist2 > 0.f)) return std::nullopt;
  cs.dist = std::sqrt(dist2);
  cs.wi = d / cs.dist;
  cs.We = We(cs.p_lens, -cs.wi, &cs.p_raster);
  if (cs.We == 0.f) return std::nullopt;
  cs.pdf = dist2 / (cos_theta(-cs.wi) * lens_area());
  return cs;
}

}  // namespace lantern
