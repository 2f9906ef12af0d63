// Bilinear patches (geometry/bilinear_patch.h) as Embree user geometry: one
// primitive per patch, intersected in double precision; a hit reports the
// patch's (u, v), from which shading rebuilds the point, and the oriented
// normal as Ng.
#pragma once

#include <embree3/rtcore.h>

#include "accel/alpha_filter.h"
#include "geometry/bilinear_patch.h"

namespace lantern {

struct BilinearGeometryData {
  const BilinearPatchSet* patches;
  AlphaFilterData* alpha;  // null: opaque
};

// Creates the Embree geometry of `data` (which must outlive it), to be
// committed by the caller.
RTCGeometry new_bilinear_geometry(RTCDevice device, BilinearGeometryData* data);

}  // namespace lantern
