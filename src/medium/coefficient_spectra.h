// A medium's coefficients as spectra of their own. With sampled
// wavelengths, sigma_a and sigma_s given as colours of a space other than
// sRGB (ColorSpace "rec2020", "dci-p3", "aces2065-1") are the unbounded
// spectra that space's own table holds for them, as pbrt-v4 makes them
// (scene/builder_media.cpp); the RGB renderer, and a medium whose
// coefficients are sRGB colours, use the sRGB values.
#pragma once

#include "color/spectrum_conversion.h"

namespace lantern {

struct CoefficientSpectra {
  UnboundedSpectrum sigma_a, sigma_s;
  bool given = false;
  // Coefficient `own` (one of the two), or `rgb` by sRGB's table.
  Spectrum at(const UnboundedSpectrum& own, const RGB& rgb, const SampledWavelengths& l) const {
    return given && !l.is_rgb() ? own.at(l) : unbounded_spectrum(rgb, l);
  }
};

}  // namespace lantern
