// pbrt's bilinear patches (Shape "bilinearmesh", and quads of PLY files):
// p(u, v) = lerp(v, lerp(u, p00, p10), lerp(u, p01, p11)) over [0, 1]^2, a
// doubly ruled surface that is curved when its corners are not coplanar.
// A patch whose corners (and normals and uvs, if given) form a
// parallelogram is an affine map of the square, exactly two triangles, and
// is stored as those; every other patch is traced as itself through Embree
// user geometry (accel/bilinear_geometry.h).
#pragma once

#include <glm/gtc/type_precision.hpp>
#include <glm/vec3.hpp>
#include <vector>

#include "math/common.h"

namespace lantern {

struct SurfacePoint;

struct BilinearPatchSet {
  std::vector<Vec3> positions;      // in the space the set is stored in
  std::vector<Vec3> normals;        // empty, or one per vertex (already flipped by ReverseOrientation)
  std::vector<Vec2> uvs;            // empty, or one per vertex
  std::vector<glm::uvec4> patches;  // vertex indices in pbrt's order: p00, p10, p01, p11
  bool flip_normal = false;         // ReverseOrientation xor a handedness-swapping transform (sets without N)
  // Patches from here on are a PLY file's triangles (p01 = p11): without
  // uvs they take pbrt's default triangle uvs, (0,0) (1,0) (1,1).
  uint32_t first_triangle = 0xFFFFFFFFu;
};

// The texture coordinates at a patch's corners (p00 p10 p01 p11): the set's
// uvs, or a triangle's defaults; false for a patch without (its (u, v) are
// its texture coordinates).
inline bool patch_corner_uvs(const BilinearPatchSet& s, uint32_t i, Vec2 out[4]) {
  if (!s.uvs.empty()) {
    const glm::uvec4 v = s.patches[i];
    out[0] = s.uvs[v.x], out[1] = s.uvs[v.y], out[2] = s.uvs[v.z], out[3] = s.uvs[v.w];
    return true;
  }
  if (i < s.first_triangle) return false;
  out[0] = Vec2(0, 0), out[1] = Vec2(1, 0), out[2] = out[3] = Vec2(1, 1);
  return true;
}

struct PatchCorners {
  Vec3 p00, p10, p01, p11;
};
inline PatchCorners patch_corners(const BilinearPatchSet& s, uint32_t i) {
  const glm::uvec4 v = s.patches[i];
  return {s.positions[v.x], s.positions[v.y], s.positions[v.z], s.positions[v.w]};
}

// The nearest crossing of the ray o + t d with the patch for t in
// (t_min, t_max): its t and (u, v). After Reshetov, "Cool Patches" (Ray
// Tracing Gems, 2019): the ray meets the segment from (u, 0) to (u, 1)
// where a quadratic in u vanishes; t and v follow from the two lines'
// closest points.
bool intersect_bilinear_patch(const PatchCorners& c, const glm::dvec3& o, const glm::dvec3& d, double t_min,
                              double t_max, double* t, Vec2* uv);

// dp/du x dp/dv at (u, v): affine in (u, v), since dp/du depends on v alone
// and dp/dv on u alone.
Vec3 patch_cross(const PatchCorners& c, Vec2 uv);

// The surface point at (u, v), oriented as a mesh is (towards the
// interpolated normals, else the winding normal flipped by flip_normal).
SurfacePoint bilinear_point(const BilinearPatchSet& s, uint32_t i, Vec2 uv);
// Its oriented geometric normal alone.
Vec3 bilinear_normal(const BilinearPatchSet& s, uint32_t i, Vec2 uv);

// The patch's area (Gauss-Legendre quadrature of |dp/du x dp/dv|).
float bilinear_area(const PatchCorners& c);

// A point for area lights: (u, v) drawn in proportion to the bilinear
// interpolation of |dp/du x dp/dv| at the corners, as pbrt-v4 does; the
// density per unit area is that density over |dp/du x dp/dv| at the point.
Vec2 sample_bilinear_patch(const PatchCorners& c, Vec2 u);
float bilinear_area_density(const PatchCorners& c, Vec2 uv);
// (u, v) of a point on the patch (Newton's method from the middle): how a
// density is evaluated for a point found by a ray.
Vec2 bilinear_uv_of(const PatchCorners& c, const Vec3& p);

// Whether four corner values form a parallelogram (v00 + v11 = v10 + v01,
// to rounding relative to their size).
bool is_parallelogram(const Vec3& v00, const Vec3& v10, const Vec3& v01, const Vec3& v11);

}  // namespace lantern
