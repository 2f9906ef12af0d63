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

inline SampledWavelengths sample_wavelengths(bool spectral, const PathSampler& s, int maxdepth) {
  if (!spectral) return SampledWavelengths::rgb();
  const uint32_t d = uint32_t(maxdepth);
  return SampledWavelengths::sample_visible(s.get1d(dims::wavelengths(dims::vertex(d + 2), d)));
}

}  // namespace lantern
