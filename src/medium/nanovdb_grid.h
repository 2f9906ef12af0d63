// pbrt-v4's "nanovdb" medium: a density grid read from a NanoVDB file
// (Museth 2021) through Debian's NanoVDB headers. As pbrt-v4 looks it up,
// the density is trilinear between voxel values at integer index
// coordinates (zero, the background, where no voxel is stored), inside the
// box of the active voxels [min, max + 1] of index space.
//
// That is a lattice of samples like a uniformgrid's, so the optical depth
// along a ray is integrated exactly and distances are sampled exactly
// (medium/grid_density.h): no tracking noise, and exact MIS densities. A
// grid of blocks of 8^3 cells with each block's largest sample skips the
// empty blocks, so a sparse cloud does not cost its bounding box.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "medium/grid_density.h"

namespace lantern {

struct VdbGrid {
  struct Data;  // the NanoVDB grid, its frame and its blocks (nanovdb_grid.cpp)
  std::shared_ptr<const Data> data;

  // The density at a point of render space.
  float density(const Vec3& p) const;
  // As DensityGrid::integrate: the integral of the density along o + t d
  // over [t0, t1], or with target >= 0 the t where it reaches target.
  float integrate(const Vec3& o, const Vec3& d, float t0, float t1, float target, float* t_hit) const;
  // How many blocks hold a non-zero sample, of how many.
  size_t occupied_blocks(size_t* total) const;
  // The box of blocks: render space from its unit coordinates, and the
  // blocks per axis; and each block's largest |sample| (x fastest;
  // infinity everywhere when the grid's background is not zero).
  Mat4 block_box(int res[3]) const;
  const std::vector<float>& block_maxima() const;

  // Reads float grid `name` of a NanoVDB file; std::runtime_error with
  // what is wrong (unreadable, malformed, no such grid, not float, ...).
  static VdbGrid load(const std::string& path, const std::string& name, const Mat4& medium_from_render);
  // Whether the file has a grid of that name (the file's layout checked).
  static bool has_grid(const std::string& path, const std::string& name);
};

}  // namespace lantern
