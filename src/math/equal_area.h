// The equal-area mapping between the unit square and the sphere (Clarberg
// 2008) that pbrt-v4 uses for environment maps and its spherical camera.
#pragma once

#include "math/common.h"

namespace lantern {

Vec3 equal_area_square_to_sphere(Vec2 p);
Vec2 equal_area_sphere_to_square(const Vec3& d);

// Folds a point just outside the unit square back in, across the edge it
// crossed, which is how the mapping continues over the sphere.
inline Vec2 wrap_equal_area_square(Vec2 p) {
  if (p.x < 0.f) {
    p.x = -p.x;
    p.y = 1.f - p.y;
  } else if (p.x > 1.f) {
    p.x = 2.f - p.x;
    p.y = 1.f - p.y;
  }
  if (p.y < 0.f) {
    p.x = 1.f - p.x;
    p.y = -p.y;
  } else if (p.y > 1.f) {
    p.x = 1.f - p.x;
    p.y = 2.f - p.y;
  }
  return p;
}

}  // namespace lantern
