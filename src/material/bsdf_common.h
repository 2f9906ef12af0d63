// Types shared by every BSDF. Directions are in the local shading frame
// (z = shading normal) and both point away from the surface.
#pragma once

#include <optional>

#include "math/frame.h"

namespace lantern {

// Radiance flows from lights to the camera along eye paths; importance flows
// the other way along light paths. Refraction scales them differently.
enum class TransportMode : uint8_t { Radiance, Importance };
inline TransportMode adjoint(TransportMode m) {
  return m == TransportMode::Radiance ? TransportMode::Importance : TransportMode::Radiance;
}

// Which lobes a sample or density may use: layered BSDFs ask an interface
// for its reflection or its transmission alone.
enum class Lobes : uint8_t { Reflection = 1, Transmission = 2, All = 3 };
inline bool has(Lobes set, Lobes l) { return (uint8_t(set) & uint8_t(l)) != 0; }

// Whether a BSDF's sample_f reads its number uc (the choice among lobes or
// layers): a BSDF of one lobe declares kReadsComponentNumber = false, and
// its callers need not draw the number (math/lazy_number.h).
template <class BSDF>
constexpr bool reads_component_number() {
  if constexpr (requires { BSDF::kReadsComponentNumber; })
    return BSDF::kReadsComponentNumber;
  else
    return true;
}

struct BSDFSample {
  Spectrum f{0.f};
  Vec3 wi{0.f};
  float pdf = 0.f;
  float etap = 1.f;  // relative index of refraction along wi (1 for reflection)
  bool specular = false;
  bool transmission = false;
  // f and pdf are the product along a random walk (layered BSDFs): their
  // ratio is the right weight, but pdf is not the density of wi. MIS must
  // ask the BSDF's pdf() instead.
  bool pdf_is_proportional = false;
};

}  // namespace lantern
