// A production-island-shaped scene (see island.cpp).
#pragma once

#include <cstdint>
#include <filesystem>

namespace scenegen {

struct IslandCounts {
  size_t quads = 0, files = 0, curves = 0, prototypes = 0, instances = 0, instanced_triangles = 0;
};

// Writes OUT/scene.pbrt and its meshes/, curves/ and instances/ folders.
// prototypes <= 0: chosen from the scale (3000 at full size, at least 8).
IslandCounts write_island(const std::filesystem::path& out, double scale, int prototypes, uint32_t seed);

}  // namespace scenegen
