// Types shared by every BSDF. Directions are in the local shading frame
// (z = shading normal) and both point away from the surface.
#pragma once

#include <optional>

#include "math/frame.h"

namespace lantern {

// Radiance flows from lights to the camera along eye paths; importance flows
// the other way along light paths. Refraction scales them differently.
enum class TransportMode : uint8_t { Radiance, Importance };

struct BSDFSample {
  RGB f{0.f};
  Vec3 wi{0.f};
  float pdf = 0.f;
  float etap = 1.f;  // relative index of refraction along wi (1 for reflection)
  bool specular = false;
  bool transmission = false;
};

}  // namespace lantern
