// pbrt's cameras, looking down +z in a left-handed camera space (raster x
// grows with camera x, raster y downwards): perspective (a pinhole or a thin
// lens), orthographic (parallel rays, or a thin lens focused at the focal
// distance) and spherical (every direction from a point, equal-area or
// equirectangular). One class, the projection chosen by a switch: camera
// rays are generated per wave, never through a virtual call.
#pragma once

#include <memory>
#include <optional>

#include "math/common.h"
#include "math/motion.h"
#include "camera/lens_system.h"
#include "math/sampling.h"

namespace lantern {

// Realistic: pbrt-v4's lens system (camera/lens_system.h).
enum class Projection : uint8_t { Perspective, Orthographic, Spherical, Realistic };

struct CameraDesc {
  Projection projection = Projection::Perspective;
  bool equal_area = true;  // spherical: pbrt-v4's "equalarea" mapping, else "equirectangular"
  Mat4 world_from_camera{1.f};  // "world" here: the space the scene is held in (pbrt-v4's render space)
  // The scene file's world from that space (the gbuffer's "world"
  // coordinates; the scene is held relative to the camera's position).
  Mat4 file_world_from_render{1.f};
  float fov_degrees = 90.f;
  float lens_radius = 0.f;
  float focal_distance = 1e6f;
  bool has_screen_window = false;
  float screen_window[4] = {-1.f, 1.f, -1.f, 1.f};  // xmin xmax ymin ymax
  // A moving camera: world_from_camera along the shutter (math/motion.h;
  // world_from_camera above is its start). Null for a still camera.
  std::shared_ptr<const MotionPath> motion;
  ShutterTimes shutter;
  // Realistic: the lens as its file gives it (focused when the camera is
  // made, for the film's size), its "focusdistance", and the Film's
  // "diagonal" in scene units (its millimetres times 0.001).
  std::shared_ptr<const LensSystem> lens;
  float focus_distance = 10.f;
  float film_diagonal = 0.035f;
};

struct CameraRay {
  Vec3 o, d;  // d is unit length
  // What the ray's radiance counts for on the film: 1 but for a realistic
  // camera (cos^4 over the pupil's density), 0 for a ray its lens blocks.
  float weight = 1.f;
};

// A point on the lens chosen to see a reference point (pbrt's Sample_Wi):
// what light tracing needs to connect a light vertex to the camera.
struct CameraSample {
  Vec3 p_lens;     // world-space point on the lens
  Vec3 wi;         // unit direction from the reference point to p_lens
  float dist = 0.f;
  float pdf = 0.f;  // solid angle density at the reference point
  float We = 0.f;   // importance of the ray from p_lens towards the reference point
  Vec2 p_raster{0.f};
};

class Camera {
 public:
  Camera() = default;
  // film_margin: how far (in pixels) past the image edges samples may land,
  // i.e. the pixel filter's radius; light tracing must reach as far.
  Camera(const CameraDesc& desc, int width, int height, Vec2 film_margin = Vec2(0.f));

  // p_raster in [0, width) x [0, height).
  CameraRay generate_ray(Vec2 p_raster, Vec2 u_lens) const;
  // Importance (pbrt's We) of a ray leaving the lens in world direction d,
  // normalised over the whole film: 1 / (A * lens_area * cos^4) for a
  // perspective camera, the direction density for a spherical one (a point
  // sensor: no cosine). Returns 0 when the ray misses the film; p_raster
  // receives where it lands.
  float We(const Vec3& p_lens, const Vec3& d, Vec2* p_raster) const;
  // Density of camera ray directions over the whole film: per solid angle
  // (1 / (A cos^3) for a perspective camera, lens position density
  // 1 / lens_area, which sample_wi shares). An orthographic camera with a
  // thin lens is an area sensor (area_sensor()): its density is per unit
  // film area projected along d, 1 / (A cos), and carries no distance. A
  // pinhole orthographic camera's directions are a delta: infinity, which
  // gives the strategies that connect to the camera (t = 1) weight 0.
  float pdf_dir(const Vec3& d) const;
  bool area_sensor() const { return projection_ == Projection::Orthographic && lens_radius_ > 0.f; }
  // Whether generate_ray and sample_wi read their lens numbers: a pinhole
  // does not, and its callers need not draw them.
  bool reads_lens_numbers() const { return projection_ == Projection::Realistic || lens_radius_ > 0.f; }
  // The camera's density of its first vertex at a point dist2 away along d
  // with cosine cos_at_point there, relative to sample_wi's choice of lens
  // point: what bidirectional MIS compares a connection to the camera with.
  float pdf_area(const Vec3& d, float dist2, float cos_at_point) const {
    return pdf_dir(d) * cos_at_point / (area_sensor() ? 1.f : dist2);
  }
  float lens_area() const { return lens_radius_ > 0.f ? kPi * lens_radius_ * lens_radius_ : 1.f; }
  // A lens point that sees ref; none for a pinhole orthographic camera.
  std::optional<CameraSample> sample_wi(const Vec3& ref, Vec2 u_lens) const;
  // A spherical image continues across its edges: a camera sample drawn
  // just outside the film (the pixel filter reaches there) looks along the
  // direction of a point inside. For a splat at p within `reach` of an
  // edge, the raster points outside the film that look along the same
  // direction, so that the pixels by the edge receive its filtered share as
  // their camera samples do. Returns how many (at most 2) were written.
  int seam_images(Vec2 p, Vec2 reach, Vec2 out[2]) const;

  // A moving camera where it is at time u of the shutter; a still one as it is.
  bool moves() const { return motion_ != nullptr; }
  Camera at(float u) const;

  int width() const { return width_; }
  int height() const { return height_; }
  Vec3 position() const { return Vec3(world_from_camera_[3]); }
  Vec3 forward() const { return forward_; }

 private:
  float cos_theta(const Vec3& d) const { return glm::dot(d, forward_); }
  Vec3 perspective_direction(Vec2 screen) const;
  CameraRay realistic_ray(Vec2 p_raster, Vec2 u_lens) const;
  Vec3 spherical_direction(Vec2 p_raster) const;  // camera space
  bool spherical_raster(const Vec3& d_camera, Vec2* p_raster) const;
  bool screen_to_raster(Vec2 s, Vec2* p_raster) const;
  float orthographic_lens_We(const Vec3& o_camera, const Vec3& d_camera, Vec2* p_raster) const;
  std::optional<CameraSample> orthographic_lens_sample_wi(const Vec3& ref, Vec2 u_lens) const;

  Projection projection_ = Projection::Perspective;
  bool equal_area_ = true;

  Mat4 world_from_camera_{1.f}, camera_from_world_{1.f};
  std::shared_ptr<const MotionPath> motion_;
  Vec3 forward_{0, 0, 1};
  float film_area_ = 4.f;  // of the image rectangle on the plane z = 1
  int width_ = 1, height_ = 1;
  Vec2 margin_{0.f};
  float sx0_ = -1, sx1_ = 1, sy0_ = -1, sy1_ = 1;
  float tan_half_ = 1.f;
  float lens_radius_ = 0.f, focal_distance_ = 1e6f;
  std::shared_ptr<const LensSystem> lens_;  // focused, its exit pupil known
  Vec2 film_extent_{0.f};                  // realistic: the film's width and height
};

// The camera that sees a sample at time u: `camera` itself when it stands
// still (no copy), else its pose at u, made in `scratch`.
inline const Camera& camera_at(const Camera& camera, float u, std::optional<Camera>& scratch) {
  if (!camera.moves()) return camera;
  return scratch.emplace(camera.at(u));
}

}  // namespace lantern
