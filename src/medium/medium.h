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

namespace lantern {

struct MediumHandle {
  uint32_t bits = 0;  // 0: vacuum; else 1 + index into MediumPools::homogeneous
  static MediumHandle homogeneous(uint32_t index) { return {index + 1}; }
  bool vacuum() const { return bits == 0; }
  uint32_t index() const { return bits - 1; }
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
// "scale") and a Henyey-Greenstein phase function.
struct HomogeneousMedium {
  RGB sigma_a{0.f}, sigma_s{0.f};
  float g = 0.f;
  RGB sigma_t() const { return sigma_a + sigma_s; }
};

struct MediumPools {
  std::vector<HomogeneousMedium> homogeneous;
  MediumHandle camera;  // the medium camera rays start in

  bool empty() const { return homogeneous.empty(); }
  const HomogeneousMedium& at(MediumHandle h) const { return homogeneous[h.index()]; }
  RGB sigma_t(MediumHandle h) const { return h.vacuum() ? RGB(0.f) : at(h).sigma_t(); }
};

}  // namespace lantern
