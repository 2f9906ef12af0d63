// pbrt-v4's "uniformgrid" density: nx x ny x nz samples at the centres of
// the cells that divide the box [p0, p1] of the medium's space, trilinear
// between neighbouring samples and falling to zero half a cell beyond the
// outer ones (as pbrt-v4's SampledGrid looks them up).
//
// Along a ray, inside one cell of the lattice of samples, the density is a
// cubic in the distance (a product of three linear interpolations). So its
// integral, the optical depth up to the medium's coefficients, is exact.
// So is the point where that integral reaches a given value (a monotone
// quartic, solved by safeguarded Newton steps). Distance sampling and
// transmittance therefore have no tracking noise, and the distance
// densities bidirectional MIS needs are known in closed form
// (docs/media.md). Cells whose eight samples are zero cost one test.
#pragma once

#include <cstdint>
#include <vector>

#include "math/common.h"

namespace lantern {

struct DensityGrid {
  int nx = 1, ny = 1, nz = 1;
  std::vector<float> values;  // x varies fastest, then y, then z (pbrt's order)
  Vec3 p0{0.f}, p1{1.f};      // the box, in the medium's space
  Mat4 medium_from_render{1.f};

  // Sample (x, y, z); zero outside the grid.
  float sample(int x, int y, int z) const {
    if (x < 0 || y < 0 || z < 0 || x >= nx || y >= ny || z >= nz) return 0.f;
    return values[(size_t(z) * size_t(ny) + size_t(y)) * size_t(nx) + size_t(x)];
  }
  // The density at a point of render space.
  float density(const Vec3& p) const;
  // The integral of the density along o + t d (render space; d need not be
  // unit length, t is in its units) over [t0, t1]. With target >= 0, stops
  // where the integral reaches target: *t_hit is that t and target is
  // returned; otherwise *t_hit is infinity.
  float integrate(const Vec3& o, const Vec3& d, float t0, float t1, float target, float* t_hit) const;
};

}  // namespace lantern
