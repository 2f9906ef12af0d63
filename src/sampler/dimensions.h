// Which sampler dimensions each decision of a path uses. Fixed per purpose
// and per vertex, so that the same decision of every sample of a pixel
// reads one well-distributed dimension: the eye subpath's and the light
// subpath's vertices at the same depth read disjoint dimensions, and how
// long one subpath was never shifts the other's.
#pragma once

#include <cstdint>

namespace lantern::dims {

// The camera sample.
inline constexpr uint32_t kFilm = 0;  // 2D
inline constexpr uint32_t kLens = 2;  // 2D

// The start of a light subpath (bdpt, lt). Under a time limit the light
// and the point (kLightSelect, kLightPosition) read zsobol in a layout of
// their own (make_light_start_spec, sampler/sampler.h).
inline constexpr uint32_t kLightSelect = 4;      // 1D: the point's first coordinate after an unlikely choice (light_choice.h)
inline constexpr uint32_t kLightPosition = 5;    // 2D: the choice of light, and the point
inline constexpr uint32_t kLightDirection = 7;   // 2D
inline constexpr uint32_t kLightStartLens = 9;   // 2D: its camera connection (t = 1)

// Vertex `depth` (1 for the first hit) of either subpath owns a block.
inline constexpr uint32_t kVertexBase = 11;
inline constexpr uint32_t kVertexBlock = 13;
inline constexpr uint32_t vertex(uint32_t depth) { return kVertexBase + kVertexBlock * depth; }

// Within an eye vertex's block: next-event estimation (bdpt: s = 1) and
// continuing the path.
inline constexpr uint32_t kEyeLightSelect = 0;    // 1D: as kLightSelect
inline constexpr uint32_t kEyeLightPosition = 1;  // 2D: as kLightPosition
inline constexpr uint32_t kEyeBsdfComponent = 3;  // 1D
inline constexpr uint32_t kEyeBsdfDirection = 4;  // 2D
inline constexpr uint32_t kEyeRoulette = 6;       // 1D
// Within a light vertex's block: its camera connection, then continuing.
inline constexpr uint32_t kLightLens = 7;           // 2D
inline constexpr uint32_t kLightBsdfComponent = 9;  // 1D
inline constexpr uint32_t kLightBsdfDirection = 10;  // 2D
inline constexpr uint32_t kLightRoulette = 12;      // 1D

// Distance sampling in participating media: one number per segment of a
// subpath (segment k leaves vertex k), eye and light interleaved. They
// follow every vertex block a render can use (base = vertex(maxdepth + 2)),
// so a scene without media reads exactly the dimensions it always did.
inline constexpr uint32_t distance(uint32_t base, uint32_t segment, bool light) { return base + 2 * segment + (light ? 1 : 0); }

// The third coordinate of a point sampled in an emissive medium (light
// sampling picks the point with kEyeLightPosition's or kLightPosition's two
// numbers and this one): one per vertex of either subpath (vertex 0: the
// light subpath's start), after the distance numbers, so scenes without
// emissive media read exactly the dimensions they did.
inline constexpr uint32_t volume_point(uint32_t base, uint32_t maxdepth, uint32_t vertex, bool light) {
  return base + 2 * (maxdepth + 3) + 2 * vertex + (light ? 1 : 0);
}

// The spectral renderer's wavelengths (one number per camera sample),
// after every number above, so the RGB renderer reads exactly the
// dimensions it always did.
inline constexpr uint32_t wavelengths(uint32_t base, uint32_t maxdepth) { return base + 4 * (maxdepth + 3); }

// The camera sample's time in the shutter (one number), read only when
// something in the scene moves, so still scenes read exactly the
// dimensions they did.
inline constexpr uint32_t shutter(uint32_t base, uint32_t maxdepth) { return wavelengths(base, maxdepth) + 1; }

}  // namespace lantern::dims
