// Two smoke blobs in one NanoVDB density grid, far apart in a sparse tree
// (so that most of the box between them is empty): the grid that
// perf/media/nanovdb-blobs.pbrt renders and the nanovdb tests read.
// Voxel size 0.02, index (0, 0, 0) at the world origin: the blobs span
// about x in [0.1, 2.1], y and z in [0.1, 0.8] of the grid's space.
#pragma once

#include <nanovdb/NanoVDB.h>
#include <nanovdb/util/GridBuilder.h>
#include <nanovdb/util/IO.h>

#include <cmath>
#include <string>
#include <vector>

namespace lantern::nvdb_blobs {

// Density at index point (i, j, k): smooth bumps with a ripple.
inline float density(int i, int j, int k) {
  auto bump = [](double x, double y, double z, double cx, double cy, double cz, double r) {
    const double d2 = ((x - cx) * (x - cx) + (y - cy) * (y - cy) + (z - cz) * (z - cz)) / (r * r);
    return d2 < 1.0 ? (1.0 - d2) * (1.0 - d2) : 0.0;
  };
  const double ripple = 0.75 + 0.25 * std::sin(0.45 * i + 0.3 * j) * std::cos(0.35 * k - 0.2 * i);
  const double v = 4.0 * bump(i, j, k, 20, 22, 20, 15) * ripple + 6.0 * bump(i, j, k, 92, 18, 22, 9);
  return float(std::round(v * 1000.0) / 1000.0);
}

// Temperature at index point (i, j, k) for the burning variant: the small
// blob glows, hottest (2400 K) at its core; none elsewhere.
inline float temperature(int i, int j, int k) {
  const double d2 = ((i - 92.0) * (i - 92.0) + (j - 18.0) * (j - 18.0) + (k - 22.0) * (k - 22.0)) / 81.0;
  return d2 < 1.0 ? float(std::round(2400.0 * (1.0 - d2))) : 0.f;
}

// Writes the grid, named "density", to `path`.
inline void write(const std::string& path) {
  nanovdb::GridBuilder<float> builder(0.f);
  auto acc = builder.getAccessor();
  for (int k = 0; k < 42; ++k)
    for (int j = 0; j < 40; ++j)
      for (int i = 0; i < 104; ++i)
        if (const float v = density(i, j, k); v > 0.f) acc.setValue(nanovdb::Coord(i, j, k), v);
  nanovdb::io::writeGrid(path, builder.getHandle<>(0.02, nanovdb::Vec3d(0.0), "density"));
}

// Writes the burning variant: the same "density" and a "temperature"
// grid (same voxels and transform) in one file.
inline void write_burning(const std::string& path) {
  nanovdb::GridBuilder<float> dens(0.f), temp(0.f);
  auto da = dens.getAccessor();
  auto ta = temp.getAccessor();
  for (int k = 0; k < 42; ++k)
    for (int j = 0; j < 40; ++j)
      for (int i = 0; i < 104; ++i) {
        if (const float v = density(i, j, k); v > 0.f) da.setValue(nanovdb::Coord(i, j, k), v);
        if (const float t = temperature(i, j, k); t > 0.f) ta.setValue(nanovdb::Coord(i, j, k), t);
      }
  std::vector<nanovdb::GridHandle<>> handles;
  handles.push_back(dens.getHandle<>(0.02, nanovdb::Vec3d(0.0), "density"));
  handles.push_back(temp.getHandle<>(0.02, nanovdb::Vec3d(0.0), "temperature"));
  nanovdb::io::writeGrids(path, handles);
}

}  // namespace lantern::nvdb_blobs
