// The wavelengths each sample of a wave carries (color/sampled_wavelengths.h):
// none in the RGB renderer; in the spectral one, drawn from the sample's
// own dimension. Vertex merging joins the light vertices of a wave's other
// samples, whose wavelengths must then be the same: with merging every
// sample of a wave takes its first sample's wavelengths (as pbrt-v4's SPPM
// takes one set per iteration; docs/spectral.md).
#pragma once

#include "color/sampled_wavelengths.h"
#include "sampler/dimensions.h"
#include "sampler/sampler.h"

namespace lantern {

// Uniform over [lo, hi] when hi > lo (Film "spectral"), else from the
// eye's sensitivity.
struct WavelengthRange {
  float lo = 0.f, hi = 0.f;
  bool uniform() const { return hi > lo; }
};

inline SampledWavelengths sample_wavelengths(bool spectral, const PathSampler& s, int maxdepth,
                                             WavelengthRange range = {}) {
  if (!spectral) return SampledWavelengths::rgb();
  const uint32_t d = uint32_t(maxdepth);
  const float u = s.get1d(dims::wavelengths(dims::vertex(d + 2), d));
  return range.uniform() ? SampledWavelengths::sample_uniform(u, range.lo, range.hi)
                         : SampledWavelengths::sample_visible(u);
}

}  // namespace lantern
