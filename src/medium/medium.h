// Participating media component: a handle into one parameter pool per
// medium kind, the interface a shape puts between two media, and the media
// of the camera and of the lights. A scene without media has empty pools
// and every integrator runs its vacuum code path.
//
// Which medium a ray travels in follows pbrt's rule: a ray leaving the
// camera is in the camera's medium; a ray crossing or leaving a shape whose
// interface is a transition (inside differs from outside) enters the side
// its direction points to; any other surface keeps the ray's medium.
#pragma once

#include <cstdint>
#include <vector>

#include "math/common.h"
#include "medium/grid_density.h"

namespace lantern {

enum class MediumKind : uint8_t { Homogeneous = 0, Grid = 1 };

struct MediumHandle {
  uint32_t bits = 0;  // 0: vacuum; else kind << 28 | (1 + index into the kind's pool)
  static MediumHandle make(MediumKind k, uint32_t index) { return {uint32_t(k) << 28 | (index + 1)}; }
  static MediumHandle homogeneous(uint32_t index) { return make(MediumKind::Homogeneous, index); }
  bool vacuum() const { return bits == 0; }
  MediumKind kind() const { return MediumKind(bits >> 28); }
  uint32_t index() const { return (bits & 0x0FFFFFFFu) - 1; }
  bool operator==(MediumHandle o) const { return bits == o.bits; }
  bool operator!=(MediumHandle o) const { return bits != o.bits; }
};

// pbrt's MediumInterface of a shape; `n` below is the shape's geometric
// normal, which points to the outside.
struct MediumInterface {
  MediumHandle inside, outside;
  bool transition() const { return inside != outside; }
  // The medium a ray along w enters at the surface, given the medium it was in.
  MediumHandle after(const Vec3& n, const Vec3& w, MediumHandle current) const {
    if (!transition()) return current;
    return glm::dot(n, w) > 0.f ? outside : inside;
  }
};

// pbrt-v4's "homogeneous": constant coefficients (per unit length, after
// "scale") and a Henyey-Greenstein phase function. A grid medium's
// coefficients are these per unit density.
struct HomogeneousMedium {
  RGB sigma_a{0.f}, sigma_s{0.f};
  float g = 0.f;
  RGB sigma_t() const { return sigma_a + sigma_s; }
};

// pbrt-v4's "uniformgrid": the coefficients scaled by a density grid.
struct GridMedium {
  HomogeneousMedium per_density;
  DensityGrid density;
};

struct MediumPools {
  std::vector<HomogeneousMedium> homogeneous;
  std::vector<GridMedium> grid;
  MediumHandle camera;  // the medium camera rays start in

  bool empty() const { return homogeneous.empty() && grid.empty(); }
  // The coefficients per unit density, and the phase function's g.
  const HomogeneousMedium& coefficients(MediumHandle h) const {
    return h.kind() == MediumKind::Grid ? grid[h.index()].per_density : homogeneous[h.index()];
  }
  // The density at p (1 in a homogeneous medium).
  float density(MediumHandle h, const Vec3& p) const {
    return h.kind() == MediumKind::Grid ? grid[h.index()].density.density(p) : 1.f;
  }
  // The integral of the density along o + s d (d unit length, s a
  // distance) over [s0, s1]; with target >= 0, stops where it reaches
  // target (*s_hit: there, or infinity).
  float density_integral(MediumHandle h, const Vec3& o, const Vec3& d, float s0, float s1, float target,
                         float* s_hit) const {
    if (h.kind() == MediumKind::Grid) return grid[h.index()].density.integrate(o, d, s0, s1, target, s_hit);
    const float len = s1 - s0;
    *s_hit = target >= 0.f && target < len ? s0 + target : kInfinity;
    return *s_hit < kInfinity ? target : len;
  }
};

}  // namespace lantern
