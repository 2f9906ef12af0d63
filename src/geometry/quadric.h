// Quadrics: pbrt's sphere (any part of one, under any invertible
// transform), cylinder and disk, as exact surfaces rather than
// tessellations. Each lives in its own object space with pbrt's parameters
// and is placed by a transform. Rays meet it there in double precision
// (geometry/quadric.cpp, through Embree user geometry); every point of the
// surface, hit or sampled, is rebuilt from its (u, v) by quadric_point, so
// a hit and a light sample at the same place agree exactly
// (geometry/surface.h).
#pragma once

#include <glm/mat3x3.hpp>
#include <glm/mat4x4.hpp>

#include "math/common.h"

namespace lantern {

enum class QuadricKind : uint8_t { Sphere, Cylinder, Disk };

struct Quadric {
  QuadricKind kind = QuadricKind::Sphere;
  float radius = 1.f;        // the disk's outer radius
  float inner_radius = 0.f;  // disk
  float z_min = -1.f, z_max = 1.f;  // sphere, cylinder; a disk's height is z_min (= z_max)
  float theta_z_min = kPi, theta_z_max = 0.f;  // sphere: the polar angles of z_min and z_max
  float phi_max = 2.f * kPi;
  bool flip_normal = false;  // ReverseOrientation xor a handedness-swapping transform, as in pbrt
  glm::dmat4 world_from_object{1.0}, object_from_world{1.0};
  glm::mat3 linear{1.f};           // the transform's linear part
  glm::mat3 normal_to_world{1.f};  // its inverse transpose
  float inv_area_scale = 1.f;  // 1 / (object area * |det linear|)
  float world_area = 0.f;
  float error_scale = 0.f;  // world-space magnitude the shape's rounding errors scale with
};

// Fills in the derived members (transforms, areas) of a quadric whose kind,
// parameters and flip_normal are set.
enum class QuadricCheck { Ok, Singular, NoArea, OutOfRange };
QuadricCheck finish_quadric(Quadric& q, const glm::dmat4& world_from_object);

float quadric_object_area(const Quadric& q);

// The object-space point and outward normal at surface coordinates uv.
Vec3 quadric_object_point(const Quadric& q, Vec2 uv);
Vec3 quadric_object_normal(const Quadric& q, const Vec3& p);

// Surface coordinates uniformly distributed over the object-space area.
Vec2 quadric_sample_uv(const Quadric& q, Vec2 u);

// The density per unit world area with which quadric_sample_uv places a
// point of world normal n (either orientation). An area element scales by
// |det L| / |L^T n| under the linear map L, so the density is constant
// only under uniform scale.
inline float quadric_area_density(const Quadric& q, const Vec3& n) {
  return glm::length(glm::transpose(q.linear) * n) * q.inv_area_scale;
}

// World-space bounds (padded for rounding).
void quadric_bounds(const Quadric& q, Vec3* lo, Vec3* hi);

// The first intersection of the ray o + t d with t in (t_min, t_max), all
// in world space: its t and surface coordinates.
struct QuadricHit {
  double t;
  Vec2 uv;
};
bool intersect_quadric(const Quadric& q, const glm::dvec3& o, const glm::dvec3& d, double t_min, double t_max,
                       QuadricHit* hit);

}  // namespace lantern
