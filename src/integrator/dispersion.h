// Dispersion in the spectral renderer. A sample carries kSpectrumSamples
// wavelengths; where its path scatters at a surface whose index of
// refraction varies with wavelength, the direction it takes is right for
// the first wavelength only (material/bsdf_kernel.h reads the index
// there). pbrt-v4 then drops the others: their densities become zero and
// the first one's is divided by their number, so the film's estimate is
// the first channel alone, times kSpectrumSamples (Physically Based
// Rendering, 4th edition: sampled wavelengths and the dielectric BSDF; the
// hero wavelength of Wilkie et al. 2014, its companions terminated).
//
// Lantern leaves the wavelengths as they are and puts that into the
// throughput instead: at the first dispersive vertex of a subpath its
// throughput b becomes (N b_0, 0, ..., 0), N = kSpectrumSamples, which the
// film turns into exactly pbrt-v4's value. Every estimate made from the
// subpath afterwards (emission it finds, light samples, connections to
// the camera) carries it. A path joined from an eye and a light subpath
// that were both reduced would carry N twice: connections and merges
// divide one out. The rule depends on the full path alone (does it
// scatter at a dispersive surface?), so every strategy that can make a
// path treats it alike, and bidirectional MIS, whose densities are all
// taken at the first wavelength, stays exact.
#pragma once

#include <cstdint>

#include "material/material.h"
#include "math/spectrum.h"

namespace lantern {

inline Spectrum first_wavelength_only(const Spectrum& b) {
  Spectrum r(0.f);
  r[0] = float(kSpectrumSamples) * b[0];
  return r;
}

// Called where a subpath scatters at a hit of material m (after the
// emission found there is counted, which the path does not scatter to
// reach): reduces the throughput once per subpath. `dispersed` is the
// subpath's flag. Only spectral renders have dispersive materials at work.
inline void scatter_at(const MaterialPools& pools, MaterialHandle m, bool spectral, Spectrum& beta, uint8_t& dispersed) {
  if (!spectral || dispersed || !pools.dispersive(m)) return;
  beta = first_wavelength_only(beta);
  dispersed = 1;
}

// The factor on the product of an eye and a light subpath's throughputs.
inline float joined_dispersion(bool eye_dispersed, bool light_dispersed) {
  return eye_dispersed && light_dispersed ? 1.f / float(kSpectrumSamples) : 1.f;
}

}  // namespace lantern
