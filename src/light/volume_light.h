// An emissive medium as a light. Bidirectional strategies need to choose
// points of emission (next-event estimation, and light subpaths that start
// in the medium), so each emissive medium becomes a light with a box it
// samples: a grid's box, or for a homogeneous medium the box around the
// shapes that bound it. The box is cut into blocks, chosen in proportion
// to a bound of sigma_a Le in each, and a point is uniform in its block.
//
// The point may lie outside the medium itself (the box around a sphere of
// fog, or an object inside the smoke): emission there is zero, and the
// integrators find which medium a point is in by the rays that reach it
// (docs/media.md, "Emissive media"). The density is exact either way, so
// every MIS weight stays exact.
#pragma once

#include <vector>

#include "math/distribution.h"
#include "medium/medium.h"

namespace lantern {

struct VolumeLight {
  MediumHandle medium;
  Mat4 render_from_unit{1.f}, unit_from_render{1.f};  // the box is [0,1]^3 in unit coordinates
  float volume = 0.f;  // of the box, in render space
  int res[3] = {1, 1, 1};
  Distribution1D blocks;  // x fastest
  float power = 0.f;      // 4 pi times the integral of the bound over the box, mean over channels
  Vec3 lo{0.f}, hi{0.f};  // the box's bounds in render space
};

// The light of emissive medium h: a grid's box, or the render-space box
// lo..hi for a homogeneous medium. False when nothing in it can emit.
bool make_volume_light(const MediumPools& media, MediumHandle h, const Vec3& lo, const Vec3& hi, VolumeLight* out);

// A point of the box from three uniform numbers, and its density per unit
// volume (render space).
Vec3 sample_volume_point(const VolumeLight& v, const Vec3& u, float* pdf);
// The density per unit volume with which sample_volume_point picks p.
float volume_point_density(const VolumeLight& v, const Vec3& p);

}  // namespace lantern
