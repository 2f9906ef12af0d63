// How much light a thick slab of a homogeneous medium under a smooth
// dielectric boundary gives back: what a subsurface material's
// "reflectance" asks for, and the single-scattering albedo that gives it.
#pragma once

#include <vector>

namespace lantern {

// The fraction of the light entering a semi-infinite medium (from a
// uniform sky, refracted by a smooth boundary of relative index eta) that
// leaves it again, for single-scattering albedo `albedo` and
// Henyey-Greenstein asymmetry g: a random walk of `walks` paths, each
// reflected inside the boundary with Fresnel's probability.
// Deterministic: the same arguments give the same number.
float slab_albedo(float albedo, float eta, float g, int walks);

// slab_albedo tabulated over the single-scattering albedo for one
// boundary and phase function, and inverted.
class SlabAlbedoTable {
 public:
  SlabAlbedoTable(float eta, float g);
  // The single-scattering albedo whose slab gives back `reflectance`
  // (clamped to [0, 1]).
  float single_scattering_albedo(float reflectance) const;

 private:
  std::vector<float> albedo_, slab_;  // increasing together
};

}  // namespace lantern
