// Geometry component pools. Each Shape directive becomes an entity whose
// geometry lives in exactly one pool; the `geometries` table points into the
// pools: a table lookup, no virtual call. Instancing adds prototypes (ranges
// of that table) and instances (a prototype and a transform).
#pragma once

#include <glm/gtc/matrix_inverse.hpp>
#include <glm/gtc/type_precision.hpp>
#include <optional>
#include <vector>

#include "geometry/bilinear_patch.h"
#include "geometry/curve.h"
#include "geometry/quadric.h"
#include "geometry/triangle_mesh.h"
#include "material/material.h"
#include "math/common.h"
#include "math/motion.h"
#include "medium/medium.h"

namespace lantern {

// Sphere: a full sphere under uniform scale, traced by Embree's own sphere
// primitive; every other sphere, cylinder and disk is a Quadric. Curve: a
// CurveSet, one or more of pbrt's curves. Bilinear: a BilinearPatchSet of
// patches that are not parallelograms (those are meshes).
enum class ShapeKind : uint8_t { Mesh, Sphere, Quadric, Curve, Bilinear };

struct Geometry {
  ShapeKind kind;
  uint32_t index;            // into meshes, spheres, quadrics, curves or patches
  MaterialHandle material;
  int32_t light_offset = -1;  // area light of primitive i is lights.area[light_offset + i]
  int32_t alpha = -1;         // index into ShapePools::alpha_masks, or -1: opaque
  MediumInterface media;      // vacuum on both sides unless the scene gives media
};

// pbrt's shape parameter "alpha": where it is below 1 the surface is cut
// out, fully (0) or stochastically (accel/alpha_filter.h).
struct AlphaMask {
  FloatTextureRef alpha;
};

// A named object (pbrt's ObjectBegin/ObjectEnd): the geometries
// [first, first + count), in the object's own space, built once into an
// Embree scene of their own.
struct Prototype {
  uint32_t first = 0, count = 0;
};

// One ObjectInstance as stored: a prototype and the affine map that places
// it (world_from_object's upper three rows, columns as in Embree's
// RTC_FORMAT_FLOAT3X4_COLUMN_MAJOR). 56 bytes: a production scene holds
// tens of millions (docs/performance.md, "Production scale"); whatever
// else shading needs is derived per hit (Instance::placed). A moving instance
// (and a moving shape, which becomes an instance of its own prototype) has
// a motion path, and its matrix here is the one at the shutter's start.
struct Placement {
  static constexpr uint32_t kStill = 0xFFFFFFFFu;
  uint32_t prototype;
  uint32_t motion = kStill;  // index into ShapePools::motions
  glm::mat4x3 world_from_object;

  static Placement of(uint32_t prototype, const Mat4& M, uint32_t motion = kStill) {
    return {prototype, motion, glm::mat4x3(M)};
  }
  Mat4 matrix() const { return Mat4(world_from_object); }
};

// An instance as shading sees it: hits come back in the prototype's space
// and are carried into the world with these matrices.
struct Instance {
  static constexpr uint32_t kStill = Placement::kStill;
  uint32_t prototype;
  Mat4 world_from_object;
  glm::mat3 normal_to_world;  // inverse transpose of the upper 3x3
  float stretch;              // the largest length an object-space unit vector takes in the world
  float offset;               // the largest coordinate of the translation
  uint32_t motion = kStill;   // index into ShapePools::motions

  static Instance placed(uint32_t prototype, const Mat4& M, uint32_t motion = kStill) {
    const float stretch = max_num(glm::length(Vec3(M[0])), max_num(glm::length(Vec3(M[1])), glm::length(Vec3(M[2]))));
    return {prototype, M, glm::inverseTranspose(glm::mat3(M)), stretch, max_abs_component(Vec3(M[3])), motion};
  }
};

struct ShapePools {
  std::vector<TriangleMesh> meshes;
  std::vector<Sphere> spheres;
  std::vector<Quadric> quadrics;
  std::vector<CurveSet> curves;
  std::vector<BilinearPatchSet> patches;
  // Top-level geometries and prototypes' geometries alike: a hit's geomID
  // is rewritten to this index (see RayStream), so shading never asks
  // which kind of geometry it was.
  std::vector<Geometry> geometries;
  std::vector<AlphaMask> alpha_masks;  // only for geometries with an alpha below 1
  std::vector<uint8_t> in_prototype;  // per geometry: 1 if it belongs to a prototype (not traced directly)
  std::vector<Prototype> prototypes;
  std::vector<Placement> instances;
  std::vector<MotionPath> motions;  // of the moving instances
};

// Instance k where it is at time u of the shutter (math/motion.h).
inline Instance instance_at(const ShapePools& shapes, uint32_t k, float u) {
  const Placement& in = shapes.instances[k];
  if (in.motion == Placement::kStill) return Instance::placed(in.prototype, in.matrix());
  return Instance::placed(in.prototype, shapes.motions[in.motion].at(u), in.motion);
}

}  // namespace lantern
