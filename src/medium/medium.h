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

#include "color/densely_sampled_spectrum.h"
#include "math/common.h"
#include "math/rng.h"
#include "medium/cloud.h"
#include "medium/coefficient_spectra.h"
#include "medium/grid_density.h"
#include "medium/nanovdb_grid.h"
#include "medium/tracking.h"
#include "medium/volume_emission.h"

namespace lantern {

enum class MediumKind : uint8_t { Homogeneous = 0, Grid = 1, RgbGrid = 2, Cloud = 3, Vdb = 4 };

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
  CoefficientSpectra spectra;  // of another colour space, with sampled wavelengths
  float g = 0.f;
  RGB Le{0.f};  // emitted radiance per unit sigma_a ("Le" times "Lescale"); unused per density
  int32_t Le_spectrum = -1;  // Le given as a spectrum: index into MediumPools::spectra
  Spectrum sigma_a_at(const SampledWavelengths& l) const { return spectra.at(spectra.sigma_a, sigma_a, l); }
  Spectrum sigma_s_at(const SampledWavelengths& l) const { return spectra.at(spectra.sigma_s, sigma_s, l); }
  Spectrum sigma_t(const SampledWavelengths& l) const { return sigma_a_at(l) + sigma_s_at(l); }
};

// pbrt-v4's "uniformgrid": the coefficients scaled by a density grid.
struct GridMedium {
  HomogeneousMedium per_density;
  DensityGrid density;
  GridEmission emission;
};

// pbrt-v4's "nanovdb": the coefficients scaled by a NanoVDB density grid.
struct VdbMedium {
  HomogeneousMedium per_density;
  VdbGrid density;
  // Emission: a black body at a temperature grid's value, (value -
  // offset) * temperature_scale kelvin, above 100 K, times Le_scale.
  VdbGrid temperature;  // no data: none
  TemperatureEmission heat;
  float Le_scale = 0.f;
  bool emits() const { return temperature.data && Le_scale > 0.f && heat.emits(); }
  RGB Le(const Vec3& p) const { return heat.at(temperature.density(p)) * Le_scale; }
  Spectrum Le(const Vec3& p, const SampledWavelengths& l) const {
    return l.is_rgb() ? illuminant_spectrum(Le(p), l) : heat.sampled(temperature.density(p), l) * Le_scale;
  }
};

// pbrt-v4's "rgbgrid": RGB coefficients on a grid.
// pbrt-v4's rgbgrid emits its Le samples times this (the integral of CIE
// y-bar over wavelength, in nm), where its other media normalise an Le to
// luminance 1 (scene/builder_media.cpp).
inline constexpr float kPbrtRgbGridLeFactor = 106.856895f;

struct RgbGridMedium {
  RgbGrid grid;
  float g = 0.f;
  float Le_scale = 0.f;  // "Lescale" times kPbrtRgbGridLeFactor, times the grid's Le samples
};

struct MediumPools {
  std::vector<HomogeneousMedium> homogeneous;
  std::vector<GridMedium> grid;
  std::vector<RgbGridMedium> rgb_grid;
  std::vector<CloudMedium> cloud;
  std::vector<VdbMedium> vdb;
  MediumHandle camera;  // the medium camera rays start in
  // Emission given as spectra (emitted_spectrum, color/densely_sampled_spectrum.h).
  std::vector<DenselySampledSpectrum> spectra;

  bool empty() const { return homogeneous.empty() && grid.empty() && rgb_grid.empty() && cloud.empty() && vdb.empty(); }

  // The Henyey-Greenstein asymmetry of the medium's phase function.
  float g(MediumHandle h) const {
    switch (h.kind()) {
      case MediumKind::Grid: return grid[h.index()].per_density.g;
      case MediumKind::RgbGrid: return rgb_grid[h.index()].g;
      case MediumKind::Cloud: return cloud[h.index()].g;
      case MediumKind::Vdb: return vdb[h.index()].per_density.g;
      default: return homogeneous[h.index()].g;
    }
  }
  // The coefficients at point p.
  void coefficients_at(MediumHandle h, const Vec3& p, const SampledWavelengths& l, Spectrum* sigma_a,
                       Spectrum* sigma_s) const {
    switch (h.kind()) {
      case MediumKind::Grid: {
        const GridMedium& m = grid[h.index()];
        const float rho = m.density.density(p);
        *sigma_a = m.per_density.sigma_a_at(l) * rho;
        *sigma_s = m.per_density.sigma_s_at(l) * rho;
        return;
      }
      case MediumKind::RgbGrid: {
        if (!l.is_rgb()) return rgb_grid[h.index()].grid.at(p, l, sigma_a, sigma_s);
        RGB a, s;
        rgb_grid[h.index()].grid.at(p, &a, &s);
        *sigma_a = unbounded_spectrum(a, l), *sigma_s = unbounded_spectrum(s, l);
        return;
      }
      case MediumKind::Vdb: {
        const VdbMedium& m = vdb[h.index()];
        const float rho = m.density.density(p);
        *sigma_a = m.per_density.sigma_a_at(l) * rho;
        *sigma_s = m.per_density.sigma_s_at(l) * rho;
        return;
      }
      case MediumKind::Cloud: cloud[h.index()].coefficients(p, l, sigma_a, sigma_s); return;
      default:
        *sigma_a = homogeneous[h.index()].sigma_a_at(l);
        *sigma_s = homogeneous[h.index()].sigma_s_at(l);
    }
  }
  // The optical depth per channel along o + s d (d unit length, s a
  // distance, s1 possibly infinite) over [s0, s1]. With tau >= 0, stops
  // where channel c's depth reaches tau: *s_hit is there (else infinity)
  // and the depth returned is the depth up to it.
  // A tracked medium (below) answers with its proxy's depth, and only
  // with tau < 0: the transmittance bidirectional MIS uses for it.
  Spectrum optical_depth(MediumHandle h, const Vec3& o, const Vec3& d, float s0, float s1, int c, float tau,
                         const SampledWavelengths& l, float* s_hit) const;

  // Emissive media (medium/volume_emission.h): whether h emits, and its
  // Le at p (radiance per unit sigma_a; zero outside its box).
  bool emissive(MediumHandle h) const {
    switch (h.kind()) {
      case MediumKind::Homogeneous: return max_component(homogeneous[h.index()].Le) > 0.f;
      case MediumKind::Grid: return grid[h.index()].emission.emits();
      case MediumKind::RgbGrid: return rgb_grid[h.index()].Le_scale > 0.f && !rgb_grid[h.index()].grid.Le.empty();
      case MediumKind::Vdb: return vdb[h.index()].emits();
      default: return false;
    }
  }
  Spectrum Le(MediumHandle h, const Vec3& p, const SampledWavelengths& l) const {
    switch (h.kind()) {
      case MediumKind::Homogeneous: {
        const HomogeneousMedium& m = homogeneous[h.index()];
        return emitted_spectrum(m.Le, m.Le_spectrum < 0 ? nullptr : &spectra[size_t(m.Le_spectrum)], l);
      }
      case MediumKind::Grid: return grid[h.index()].emission.at(p, l);
      case MediumKind::RgbGrid: {
        const RgbGrid& g = rgb_grid[h.index()].grid;
        return (l.is_rgb() ? illuminant_spectrum(g.Le_at(p), l) : g.Le_at(p, l)) * rgb_grid[h.index()].Le_scale;
      }
      case MediumKind::Vdb:
        return vdb[h.index()].emits() ? vdb[h.index()].Le(p, l) : Spectrum(0.f);
      default: return Spectrum(0.f);
    }
  }
  bool any_emissive() const { return !emissive_media.empty(); }
  std::vector<MediumHandle> emissive_media;  // set by the scene builder

  // Media with no closed-form optical depth, which rays are tracked
  // through (medium/tracking.h).
  bool tracked(MediumHandle h) const { return h.kind() == MediumKind::Cloud; }
  // Delta tracking along o + s d (d unit length) over [0, len]: the real
  // collision's distance s (infinity: none) and the weights.
  tracking::Track track(MediumHandle h, const Vec3& o, const Vec3& d, float len, float u, const SampledWavelengths& l,
                        RandomStream& rng) const;
  // Ratio tracking over the same: an unbiased transmittance estimate.
  Spectrum ratio_track(MediumHandle h, const Vec3& o, const Vec3& d, float len, const SampledWavelengths& l,
                       RandomStream& rng) const;
};

}  // namespace lantern
