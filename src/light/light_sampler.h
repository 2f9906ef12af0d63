// How next-event estimation chooses a light for a shading point: pbrt-v4's
// light samplers. "bvh" (the default) descends a light BVH by importance
// from the point; "power" chooses in proportion to emitted power, "uniform"
// with equal probability. Lights at infinity (distant and environment)
// are outside the BVH: with n of them, "bvh" picks one of them with
// probability n / (n + 1), as pbrt-v4 does, and the BVH otherwise.
//
// Constant environment lights (no image) are never chosen: BSDF sampling
// finds them at least as well (light_sampler.cpp), and their light
// samples go to the other lights.
//
// Light subpaths (bdpt, lt) always start from a light chosen by power
// (LightPools::selection): their density is what bidirectional MIS
// compares with next-event estimation's, which this sampler gives.
#pragma once

#include "lantern/options.h"

#include <cstdint>
#include <string>

#include "light/light_bvh.h"
#include "light/lights.h"

namespace lantern {

class LightSampler {
 public:
  LightSampler(const LightPools& lights, const ShapePools& shapes, const TexturePools& tex, LightSamplerKind kind);

  // Chooses a light (index into LightPools::all) for point p with normal n
  // (zero: no surface); false when none can light p. u_remapped
  // (optional): u rescaled within the choice's share, uniform in [0, 1)
  // given the choice (light_choice.h).
  bool sample(const Vec3& p, const Vec3& n, float u, uint32_t* light, float* pmf, float* u_remapped = nullptr) const;
  // The probability that sample() chooses `light` for (p, n).
  float pmf(const Vec3& p, const Vec3& n, uint32_t light) const;
  // For lights at infinity the choice does not depend on the point.
  float pmf_infinite(uint32_t light) const { return pmf(Vec3(0.f), Vec3(0.f), light); }

  LightSamplerKind kind() const { return kind_; }
  const LightBvh& bvh() const { return bvh_; }
  double build_seconds() const { return build_seconds_; }
  size_t memory_bytes() const {
    return bvh_.memory_bytes() + (infinite_.capacity() + eligible_.capacity()) * sizeof(uint32_t);
  }

 private:
  const LightPools& lights_;
  LightSamplerKind kind_;
  LightBvh bvh_;
  std::vector<uint32_t> eligible_;  // every light but constant environments
  Distribution1D power_;            // power: over eligible_
  std::vector<uint32_t> infinite_;  // lights at infinity (bvh)
  std::vector<uint8_t> is_infinite_;
  float p_infinite_ = 0.f;          // bvh: probability of choosing among infinite_
  double build_seconds_ = 0.0;
};

// The bounds of one light with a finite position.
LightBounds light_bounds(const LightPools& lights, const ShapePools& shapes, const TexturePools& tex, uint32_t light);

}  // namespace lantern
