// One stratified 2D sample chooses a light and places the point on it.
//
// An emissive mesh is as many lights as it has triangles. When a number of
// its own chooses among them, the points one triangle receives are a random
// subset of a stratified set of points, no longer stratified: light tracing
// from a quad light (two triangles) splats its points onto the light's own
// pixels with the noise of independent samples, and next-event estimation
// loses the stratification of its points the same way. So the first
// coordinate of the point's 2D sample makes the choice, and what is left of
// it (its place within the chosen light's share of [0, 1), rescaled, which
// is uniform again given the choice) places the point: over all lights the
// points keep the 2D sample's stratification. (Reusing a number left over
// from a discrete choice is the remapping pbrt-v4's BVH light sampler and
// Lantern's already do across the tree's levels.)
//
// The rest keeps 24 - log2(1 / pmf) of a sample's 24 bits. Below
// kReuseMinPmf (14 bits left) a light's points would start to fall on a
// comb of lines, so a light chosen with a smaller probability takes its
// coordinate from the choice's own number instead, as before.
#pragma once

#include "math/lazy_number.h"

namespace lantern {

inline constexpr float kReuseMinPmf = 1.f / 1024.f;

// The first coordinate of the chosen light's point: `rest` (what the choice
// left of the coordinate that made it) or, for an unlikely choice, the
// independent number `fallback`.
inline float light_point_coordinate(float rest, float pmf, LazyNumber fallback) {
  return pmf >= kReuseMinPmf ? rest : fallback();
}

}  // namespace lantern
