// Quadrics (geometry/quadric.h) as Embree user geometry: one primitive per
// shape, whose callbacks intersect in double precision in the shape's own
// space. A hit reports pbrt's (u, v), from which shading rebuilds the
// point, and the world normal as Ng. Embree calls no filter function on
// user geometry by itself, so an alpha-cut quadric runs the alpha filter
// through rtcFilterIntersection / rtcFilterOcclusion on each candidate.
#pragma once

#include <embree3/rtcore.h>

#include "accel/alpha_filter.h"
#include "geometry/quadric.h"

namespace lantern {

struct QuadricGeometryData {
  const Quadric* quadric;
  AlphaFilterData* alpha;  // null: opaque
};

// Creates the Embree geometry of `data` (which must outlive it), to be
// committed by the caller.
RTCGeometry new_quadric_geometry(RTCDevice device, QuadricGeometryData* data);

}  // namespace lantern
