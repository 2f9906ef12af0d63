#include "camera/camera.h"

#include "math/equal_area.h"

namespace lantern {

Camera::Camera(const CameraDesc& d, int width, int height, Vec2 film_margin)
    : projection_(d.projection),
      equal_area_(d.equal_area),
      world_from_camera_(d.world_from_camera),
      motion_(d.motion),
      width_(width),
      height_(height),
      margin_(film_margin) {
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
  tan_half_ = projection_ == Projection::Perspective ? std::tan(glm::radians(d.fov_degrees) * 0.5f) : 1.f;
  lens_radius_ = projection_ == Projection::Spherical ? 0.f : d.lens_radius;
  focal_distance_ = d.focal_distance;
  camera_from_world_ = glm::inverse(world_from_camera_);
  forward_ = glm::normalize(Vec3(world_from_camera_ * Vec4(0.f, 0.f, 1.f, 0.f)));
  film_area_ = (sx1_ - sx0_) * (sy1_ - sy0_) * tan_half_ * tan_half_;
  if (projection_ == Projection::Realistic) {
    // The film's sides from its diagonal and the image's aspect ratio;
    // focused with rays a thousandth of the diagonal off the axis, as
    // pbrt-v4 does.
    const float ratio = float(height) / float(width);
    const float x = std::sqrt(sqr(d.film_diagonal) / (1.f + ratio * ratio));
    film_extent_ = Vec2(x, ratio * x);
    auto lens = std::make_shared<LensSystem>(*d.lens);
    lens->focus(d.focus_distance, 0.001f * d.film_diagonal);
    lens->compute_exit_pupil(0.5f * d.film_diagonal);
    lens_ = std::move(lens);
    lens_radius_ = 0.f;
  }
}

Camera Camera::at(float u) const {
  Camera c = *this;
  if (!motion_) return c;
  c.world_from_camera_ = motion_->at(u);
  c.camera_from_world_ = glm::inverse(c.world_from_camera_);
  c.forward_ = glm::normalize(Vec3(c.world_from_camera_ * Vec4(0.f, 0.f, 1.f, 0.f)));
  return c;
}

Vec3 Camera::perspective_direction(Vec2 s) const { return glm::normalize(Vec3(s.x * tan_half_, s.y * tan_half_, 1.f)); }

// pbrt-v4's mappings, with camera y and z exchanged so that the image's
// vertical runs along the camera's up axis.
Vec3 Camera::spherical_direction(Vec2 p) const {
  Vec2 uv(p.x / float(width_), p.y / float(height_));
  Vec3 d;
  if (equal_area_) {
    d = equal_area_square_to_sphere(wrap_equal_area_square(uv));
  } else {
    float theta = kPi * uv.y, phi = 2.f * kPi * uv.x;
    d = Vec3(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta));
  }
  return Vec3(d.x, d.z, d.y);
}

bool Camera::spherical_raster(const Vec3& dc, Vec2* p_raster) const {
  const Vec3 d = glm::normalize(Vec3(dc.x, dc.z, dc.y));
  Vec2 uv;
  if (equal_area_) {
    uv = equal_area_sphere_to_square(d);
  } else {
    float phi = std::atan2(d.y, d.x);
    if (phi < 0.f) phi += 2.f * kPi;
    uv = Vec2(phi * kInv2Pi, std::acos(glm::clamp(d.z, -1.f, 1.f)) * kInvPi);
  }
  *p_raster = uv * Vec2(float(width_), float(height_));
  return is_finite(Vec3(*p_raster, 0.f));
}

int Camera::seam_images(Vec2 p, Vec2 reach, Vec2 out[2]) const {
  if (projection_ != Projection::Spherical) return 0;
  const float W = float(width_), H = float(height_);
  int n = 0;
  // Equirectangular: x wraps around; across a pole, phi turns by pi.
  // Equal-area: each edge of the square folds onto itself reversed.
  if (p.x < reach.x) out[n++] = equal_area_ ? Vec2(-p.x, H - p.y) : Vec2(p.x + W, p.y);
  else if (p.x > W - reach.x) out[n++] = equal_area_ ? Vec2(2.f * W - p.x, H - p.y) : Vec2(p.x - W, p.y);
  const float x_across = equal_area_ ? W - p.x : std::fmod(p.x + 0.5f * W, W);
  if (p.y < reach.y) out[n++] = Vec2(x_across, -p.y);
  else if (p.y > H - reach.y) out[n++] = Vec2(x_across, 2.f * H - p.y);
  return n;
}

CameraRay Camera::generate_ray(Vec2 p, Vec2 u_lens) const {
  if (projection_ == Projection::Realistic) return realistic_ray(p, u_lens);
  const Vec2 s(sx0_ + (p.x / float(width_)) * (sx1_ - sx0_), sy1_ - (p.y / float(height_)) * (sy1_ - sy0_));
  Vec3 origin(0.f), dir;
  switch (projection_) {
    case Projection::Perspective: dir = perspective_direction(s); break;
    case Projection::Orthographic:
      origin = Vec3(s.x, s.y, 0.f);
      dir = Vec3(0.f, 0.f, 1.f);
      break;
    case Projection::Spherical: dir = spherical_direction(p); break;
    case Projection::Realistic: break;
  }
  if (lens_radius_ > 0.f) {
    // Through the point of the plane of focus the pinhole ray meets.
    Vec2 lens = lens_radius_ * sample_uniform_disk_concentric(u_lens);
    Vec3 focus = origin + dir * (focal_distance_ / dir.z);
    origin = Vec3(origin.x + lens.x, origin.y + lens.y, 0.f);
    dir = glm::normalize(focus - origin);
  }
  CameraRay r;
  r.o = Vec3(world_from_camera_ * Vec4(origin, 1.f));
  r.d = glm::normalize(Vec3(world_from_camera_ * Vec4(dir, 0.f)));
  return r;
}

// Through the lens system from the film point under p (the image turned
// over, as a lens turns it: raster x runs against film x); a blocked ray
// leaves from the camera along its axis with weight 0.
CameraRay Camera::realistic_ray(Vec2 p, Vec2 u_lens) const {
  const Vec2 s(p.x / float(width_), p.y / float(height_));
  const Vec3 p_film(-(s.x - 0.5f) * film_extent_.x, (s.y - 0.5f) * film_extent_.y, 0.f);
  CameraRay r;
  const std::optional<LensSystem::Sample> ls = lens_->sample_ray(p_film, u_lens);
  const Vec3 origin = ls ? ls->ray.o : Vec3(0.f), dir = ls ? ls->ray.d : Vec3(0.f, 0.f, 1.f);
  r.o = Vec3(world_from_camera_ * Vec4(origin, 1.f));
  r.d = glm::normalize(Vec3(world_from_camera_ * Vec4(dir, 0.f)));
  r.weight = ls && std::isfinite(ls->weight) ? ls->weight : 0.f;
  return r;
}

// The raster position of screen point s, if it lies on the film (with the
// filter's margin).
bool Camera::screen_to_raster(Vec2 s, Vec2* p_raster) const {
  Vec2 r((s.x - sx0_) / (sx1_ - sx0_) * float(width_), (sy1_ - s.y) / (sy1_ - sy0_) * float(height_));
  if (!(r.x > -margin_.x && r.x < float(width_) + margin_.x && r.y > -margin_.y && r.y < float(height_) + margin_.y))
    return false;
  *p_raster = r;
  return true;
}

// A thin-lens orthographic ray leaves film point f offset by lens point l
// towards (f, focal distance): its direction (-l, fd) depends on l alone,
// and for one l the origins cover the film uniformly. Over (film, lens) the
// rays have density 1 / (A_film A_lens); per unit origin area and solid
// angle that is fd^2 / (A_film A_lens cos^3), and the importance divides by
// one more cosine, as for the perspective camera.
float Camera::orthographic_lens_We(const Vec3& o_cam, const Vec3& d_cam, Vec2* p_raster) const {
  if (!(d_cam.z > 0.f)) return 0.f;
  const Vec3 focus = o_cam + d_cam * (focal_distance_ / d_cam.z);
  const Vec2 lens = Vec2(o_cam) - Vec2(focus);
  if (glm::dot(lens, lens) > sqr(lens_radius_) * (1.f + 1e-3f)) return 0.f;
  if (!screen_to_raster(Vec2(focus), p_raster)) return 0.f;
  const float cos_t = d_cam.z / glm::length(d_cam), cos2 = cos_t * cos_t;
  return sqr(focal_distance_) / (film_area_ * lens_area() * cos2 * cos2);
}

// A realistic camera has no importance in closed form (nor in pbrt-v4):
// the integrators that connect to the camera refuse it, and it reports
// none here.
float Camera::We(const Vec3& p_lens, const Vec3& d, Vec2* p_raster) const {
  if (projection_ == Projection::Realistic) return 0.f;
  if (projection_ == Projection::Orthographic) {
    if (lens_radius_ <= 0.f) return 0.f;
    return orthographic_lens_We(Vec3(camera_from_world_ * Vec4(p_lens, 1.f)), Vec3(camera_from_world_ * Vec4(d, 0.f)),
                                p_raster);
  }
  if (projection_ == Projection::Spherical) {
    Vec2 r;
    if (!spherical_raster(Vec3(camera_from_world_ * Vec4(d, 0.f)), &r)) return 0.f;
    *p_raster = r;
    return pdf_dir(d);
  }
  float cos_t = cos_theta(d);
  if (cos_t <= 0.f) return 0.f;
  // Where the ray crosses the plane of focus, seen from the lens centre,
  // gives the film position (for a pinhole, the direction itself does).
  Vec3 o = Vec3(camera_from_world_ * Vec4(p_lens, 1.f));
  Vec3 dc = Vec3(camera_from_world_ * Vec4(d, 0.f));
  Vec3 q = lens_radius_ > 0.f ? o + dc * (focal_distance_ / dc.z) : dc;
  if (!screen_to_raster(Vec2(q.x / q.z / tan_half_, q.y / q.z / tan_half_), p_raster)) return 0.f;
  float cos2 = cos_t * cos_t;
  return 1.f / (film_area_ * lens_area() * cos2 * cos2);
}

float Camera::pdf_dir(const Vec3& d) const {
  switch (projection_) {
    case Projection::Perspective: {
      float cos_t = cos_theta(d);
      return cos_t > 0.f ? 1.f / (film_area_ * cos_t * cos_t * cos_t) : 0.f;
    }
    case Projection::Orthographic: {
      if (lens_radius_ <= 0.f) return kInfinity;
      // Per unit film area, projected along d (see area_sensor()).
      float cos_t = cos_theta(d);
      return cos_t > 0.f ? 1.f / (film_area_ * cos_t) : 0.f;
    }
    case Projection::Spherical: {
      if (equal_area_) return kInv4Pi;
      // Uniform in (phi, theta): d(omega) = 2 pi^2 sin(theta) du dv.
      Vec3 dc = glm::normalize(Vec3(camera_from_world_ * Vec4(d, 0.f)));
      // theta from the camera's y axis; from the other two components, which
      // keep their precision near the poles where 1 - y^2 rounds to 0.
      float sin_theta = std::sqrt(dc.x * dc.x + dc.z * dc.z);
      return sin_theta > 0.f ? 1.f / (2.f * kPi * kPi * sin_theta) : 0.f;
    }
    case Projection::Realistic: return 0.f;
  }
  return 0.f;
}

// The lens point picks the direction (-l, fd); the ray in that direction
// through ref starts where it crosses the film plane.
std::optional<CameraSample> Camera::orthographic_lens_sample_wi(const Vec3& ref, Vec2 u_lens) const {
  const Vec3 x = Vec3(camera_from_world_ * Vec4(ref, 1.f));
  if (!(x.z > 0.f)) return std::nullopt;
  const Vec2 l = lens_radius_ * sample_uniform_disk_concentric(u_lens);
  const Vec3 d_cam(-l.x, -l.y, focal_distance_);
  const Vec3 o_cam(x.x - d_cam.x * (x.z / focal_distance_), x.y - d_cam.y * (x.z / focal_distance_), 0.f);
  CameraSample cs;
  cs.We = orthographic_lens_We(o_cam, d_cam, &cs.p_raster);
  if (cs.We == 0.f) return std::nullopt;
  cs.p_lens = Vec3(world_from_camera_ * Vec4(o_cam, 1.f));
  Vec3 d = cs.p_lens - ref;
  cs.dist = glm::length(d);
  if (!(cs.dist > 0.f)) return std::nullopt;
  cs.wi = d / cs.dist;
  // Solid angle at ref per unit lens area: fd^2 / cos^3.
  const float cos_t = focal_distance_ / glm::length(d_cam);
  cs.pdf = sqr(focal_distance_) / (lens_area() * cos_t * cos_t * cos_t);
  return cs;
}

std::optional<CameraSample> Camera::sample_wi(const Vec3& ref, Vec2 u_lens) const {
  if (projection_ == Projection::Realistic) return std::nullopt;
  if (projection_ == Projection::Orthographic) {
    if (lens_radius_ <= 0.f) return std::nullopt;
    return orthographic_lens_sample_wi(ref, u_lens);
  }
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
  // A point sensor (spherical) has no cosine.
  const float cos_lens = projection_ == Projection::Spherical ? 1.f : cos_theta(-cs.wi);
  cs.pdf = dist2 / (cos_lens * lens_area());
  return cs;
}

}  // namespace lantern
