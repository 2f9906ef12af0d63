// Still instances as one Embree user geometry, one primitive each: the
// instance's transform stays in the scene's Placement pool (56 bytes) and
// Embree keeps only its bounds in the BVH, where an Embree instance
// geometry costs some hundreds of bytes (docs/performance.md, "Production
// scale"). A ray that reaches a primitive's box is carried into the
// prototype's space and traced through the prototype's own scene, as
// Embree does for its instances; the hit reports the prototype's geometry,
// the instance as instID[0] = base + k, and u, v and Ng in the prototype's
// space, exactly as an Embree instance's hit does.
#pragma once

#include <embree3/rtcore.h>

#include <vector>

#include "entity/shapes.h"

namespace lantern {

struct InstanceGeometryData {
  const std::vector<Placement>* placements;
  std::vector<uint32_t> placement_of;       // primitive -> placement index k; empty: k = primitive
  const std::vector<RTCScene>* scenes;      // per prototype, committed
  std::vector<RTCBounds> prototype_bounds;  // per prototype, in its own space
  uint32_t instance_base = 0;               // instID[0] of placement k is base + k

  uint32_t placement(uint32_t prim) const { return placement_of.empty() ? prim : placement_of[prim]; }
};

// `count` primitives: the still instances.
RTCGeometry new_instance_geometry(RTCDevice device, InstanceGeometryData* data, uint32_t count);

}  // namespace lantern
