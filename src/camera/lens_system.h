// pbrt-v4's "realistic" camera: a system of spherical lens elements and an
// aperture stop in front of a film, traced element by element (Kolb,
// Mitchell & Hanrahan, "A Realistic Camera Model for Computer Graphics",
// SIGGRAPH 1995; Pharr, Jakob & Humphreys, Physically Based Rendering,
// 4th ed., sec. 5.3). Lens space: the film is the plane z = 0, the
// elements lie towards -z, the scene beyond them; camera space (+z ahead)
// is lens space with z negated, and every ray in and out of this class is
// in camera space (the film at z = 0, the lens towards +z). Lengths in
// scene units (the file's millimetres times 0.001, as pbrt-v4 reads them).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "math/common.h"

namespace lantern {

// One spherical interface (a plane aperture stop when the radius is 0),
// listed from the scene side to the film: its curvature radius, the
// distance along the axis to the next interface (or the film), the index
// of refraction behind it (towards the film; 0 in a file means air) and
// its aperture radius.
struct LensInterface {
  float curvature_radius = 0.f;
  float thickness = 0.f;
  float eta = 1.f;
  float aperture_radius = 0.f;
};

struct LensRay {
  Vec3 o, d;
};

// pbrt-v4's aperture image: a transmission over the square around the
// stop, [-r, r]^2, row 0 at -y; bilinear between texel centres, black
// outside; scaled so that its mean is pi / 4, the round stop's share of
// that square, so that any shape passes as much light as the round stop.
struct ApertureMask {
  int width = 0, height = 0;
  std::vector<float> values;
  // Throws std::invalid_argument for an empty or all-black mask.
  ApertureMask(int w, int h, std::vector<float> v);
  // At a point of the stop plane in units of its radius.
  float at(Vec2 p) const;
};
// pbrt-v4's built-in shapes on a 256 x 256 grid: "gaussian", "square",
// "pentagon", "star"; none for another name.
std::optional<ApertureMask> builtin_aperture(const std::string& name);

class LensSystem {
 public:
  LensSystem() = default;
  // The interfaces as read from a lens file (millimetres; 0 for eta is
  // air), the stop's diameter replaced by aperture_diameter (mm) when
  // that is smaller. Throws std::invalid_argument with what is wrong.
  LensSystem(const std::vector<float>& file_numbers, float aperture_diameter_mm);

  // Moves the film (the last interface's thickness) so that a point
  // focus_distance in front of the lens is sharp, by the thick lens
  // approximation of the system, measured with rays at height
  // probe_height from the axis. Throws std::invalid_argument when the
  // system cannot focus there.
  void focus(float focus_distance, float probe_height);
  // The exit pupil seen from film points at distances [0, film_radius]
  // from the axis, as bounding boxes on the rear element's plane (for a
  // point on the +x axis; rotated for others).
  void compute_exit_pupil(float film_radius);

  // A ray from the film point (z = 0) towards the scene
  // through the pupil, and its weight cos^4(theta) / (pdf z_rear^2) (the
  // irradiance it contributes, pdf per area of the rear plane); none
  // when the system blocks it.
  struct Sample {
    LensRay ray;  // leaving the front element, d unit length
    float weight;
  };
  std::optional<Sample> sample_ray(const Vec3& p_film, Vec2 u) const;

  // pbrt-v4's "aperture": the stop transmits by the mask instead of its
  // round opening (the exit pupil stays the round stop's, as in pbrt-v4).
  void set_aperture(ApertureMask mask) { aperture_ = std::move(mask); }

  // Through the elements, film side first or scene side first; none when
  // an element's aperture or total internal reflection stops the ray. With
  // `transmission`, an aperture mask replaces the round stop and its value
  // where the ray crosses is written there.
  std::optional<LensRay> trace_from_film(LensRay r, float* transmission = nullptr) const;
  std::optional<LensRay> trace_from_scene(LensRay r) const;

  float rear_z() const { return interfaces_.back().thickness; }
  float front_z() const;
  float rear_radius() const { return interfaces_.back().aperture_radius; }
  const std::vector<LensInterface>& interfaces() const { return interfaces_; }

 private:
  struct Box {
    Vec2 lo{0.f}, hi{0.f};
  };
  std::vector<LensInterface> interfaces_;
  std::optional<ApertureMask> aperture_;
  std::vector<Box> pupil_;  // per radial segment of the film
  float film_radius_ = 0.f;
};

// The numbers of a lens file: whitespace-separated, "#" to the end of a
// line a comment. Throws std::runtime_error naming the file and line of
// anything that is not a number.
std::vector<float> read_lens_file(const std::string& path);

}  // namespace lantern
