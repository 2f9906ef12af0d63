// What emissive media emit: pbrt-v4's "Le" of a medium, radiance emitted
// per unit of absorption, so a medium emits sigma_a(p) Le(p) per unit
// length (PBR 4th ed., sec. 11.1.2). A homogeneous medium's Le is a
// constant; a uniformgrid's is a spectrum times its "Lescale" grid, or a
// black body at its "temperature" grid's value; an rgbgrid's is an RGB
// grid times "Lescale" (medium/grid_density.h). Scenes without emissive
// media never look these up.
#pragma once

#include <optional>
#include <vector>

#include "color/densely_sampled_spectrum.h"
#include "color/sampled_wavelengths.h"
#include "color/spectrum_conversion.h"
#include "math/common.h"
#include "medium/grid_density.h"

namespace lantern {

// pbrt-v4's BlackbodySpectrum (Planck's law over its peak value) as linear
// sRGB, tabulated in kelvin from 100 K, where pbrt-v4's media start to
// emit, to the hottest temperature a grid holds; linear in between.
class BlackbodyTable {
 public:
  BlackbodyTable() = default;
  explicit BlackbodyTable(float max_kelvin);
  RGB at(float kelvin) const;
  bool empty() const { return rgb_.empty(); }

 private:
  static constexpr float kMinKelvin = 100.f;
  float step_ = 1.f;
  std::vector<RGB> rgb_;
};

// pbrt-v4's emission from temperatures (uniformgrid and nanovdb): a black
// body at (value - offset) * scale kelvin ("temperatureoffset" or
// "temperaturecutoff", "temperaturescale"), emitting above 100 K.
struct TemperatureEmission {
  float offset = 0.f, scale = 1.f;
  BlackbodyTable blackbody;  // empty: nothing is hot enough to emit

  float kelvin(float value) const { return (value - offset) * scale; }
  RGB at(float value) const { return blackbody.at(kelvin(value)); }
  // The black body itself at the wavelengths l (the spectral renderer's):
  // Planck's law over its peak, which is what `at` is the colour of.
  Spectrum sampled(float value, const SampledWavelengths& l) const;
  bool emits() const { return !blackbody.empty(); }
  // Tabulates the colours for values of magnitude at most `largest`
  // (infinity: unbounded, up to 10^6 K); false when none is hot enough.
  bool tabulate(float largest);
};

// A uniformgrid's emission, looked up at the same box coordinates as its
// density.
struct GridEmission {
  RGB Le{0.f};             // the "Le" spectrum as RGB, normalised as pbrt-v4 does (luminance 1)
  std::optional<DenselySampledSpectrum> Le_spectrum;  // "Le" given as a spectrum (emitted_spectrum)
  DensityGrid scale;       // "Lescale": one value per sample, or a single sample of 1
  DensityGrid temperature; // "temperature" samples; empty: Le is used
  TemperatureEmission heat;

  bool emits() const { return !temperature.values.empty() || max_component(Le) > 0.f; }
  // Le at a point of render space.
  RGB at(const Vec3& p) const;
  // The same at the wavelengths l: a temperature's black body exactly, an
  // "Le" given as a spectrum that spectrum, one given as RGB an RGB
  // illuminant.
  Spectrum at(const Vec3& p, const SampledWavelengths& l) const;
  // A weight for the box's region [u0, u1] (unit box coordinates) that
  // follows the largest Le there (max channel): zero only where no point
  // of the region emits.
  float bound(const Vec3& u0, const Vec3& u1) const;
};

}  // namespace lantern
