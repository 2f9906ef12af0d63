// pbrt-v4's "cloud": a procedural density in the box [p0, p1] of the
// medium's space, built from Perlin noise (Pharr, Jakob & Humphreys, PBR
// 4th ed., ch. 11): five octaves of noise at the lookup point, which
// "wispiness" first displaces by the noise's gradient; the sum falls off
// with height (y) and is clamped to [0, 1], and the bottom half is filled
// in towards y = 0. The coefficients are sigma_a and sigma_s per unit
// density.
//
// The density has no closed-form integral, so rays are tracked through it
// (medium/tracking.h) against the majorant max_c sigma_t,c (the density is
// at most 1). The distance densities that bidirectional MIS needs are
// those of a proxy: the same density sampled on a lattice and integrated
// exactly (docs/media.md, "Tracked media").
#pragma once

#include "color/spectrum_conversion.h"
#include "medium/coefficient_spectra.h"
#include "medium/grid_density.h"

namespace lantern {

// The proxy's lattice: fine enough that its transmittance is close to
// the cloud's at pbrt-v4's default frequency, cheap to walk.
constexpr int kCloudProxyResolution = 16;

struct CloudMedium {
  RGB sigma_a{1.f}, sigma_s{1.f};  // per unit density
  CoefficientSpectra spectra;      // of another colour space, with sampled wavelengths
  float g = 0.f;
  float density = 1.f, wispiness = 1.f, frequency = 5.f;
  Vec3 p0{0.f}, p1{1.f};
  Mat4 medium_from_render{1.f};
  DensityGrid proxy;  // the density on a lattice over the box: for MIS only

  // The density at a point of the medium's space.
  float density_in_medium(Vec3 p) const;
  float density_at(const Vec3& p_render) const;
  // The coefficients at a point of render space.
  void coefficients(const Vec3& p_render, const SampledWavelengths& l, Spectrum* a, Spectrum* s) const {
    const float rho = density_at(p_render);
    *a = spectra.at(spectra.sigma_a, sigma_a, l) * rho;
    *s = spectra.at(spectra.sigma_s, sigma_s, l) * rho;
  }
  Spectrum sigma_t(const SampledWavelengths& l) const {
    return spectra.at(spectra.sigma_a, sigma_a, l) + spectra.at(spectra.sigma_s, sigma_s, l);
  }
  // The grey majorant: the largest extinction of any channel.
  float sigma_bar(const SampledWavelengths& l) const { return max_component(sigma_t(l)); }
  // The part [*ta, *tb] of [t0, t1] along o + t d (render space) that lies
  // in the box; false when there is none.
  bool clip(const Vec3& o, const Vec3& d, float t0, float t1, float* ta, float* tb) const;
  // Samples the density on an n^3 lattice for the proxy.
  void build_proxy(int n);
};

}  // namespace lantern
