// Measured optical constants of the metals pbrt-v4 names (`metal-Cu-eta`,
// `metal-Au-k`, ...) and their reduction to the per-channel eta and k of
// Lantern's RGB conductor.
#pragma once

#include <optional>
#include <span>
#include <string_view>

#include "math/common.h"

namespace lantern {

// One row of a table: wavelength (nm), refractive index n, extinction k.
struct OpticalConstant {
  float nm, n, k;
};

struct ConductorRGB {
  RGB eta, k;
};

// The table behind a metal's name ("Cu", "Au", "Ag", "Al", "CuZn", and the
// transparent "MgO" and "TiO2"), or an empty span.
std::span<const OpticalConstant> optical_constants(std::string_view metal);

// Unpolarised Fresnel reflectance of a conductor n + ik seen from vacuum
// at cos(theta) = cos_theta.
double fresnel_conductor(double cos_theta, double n, double k);

// Cosine-weighted hemispherical average of fresnel_conductor.
double fresnel_conductor_average(double n, double k);

// Per-channel (eta, k) whose Fresnel curve matches the measured metal's in
// each sRGB channel: the same reflectance at normal incidence and the same
// hemispherical average, both taken from the spectra under D65
// (color/cie1931.h). Computed once per metal. Empty for unknown metals.
std::optional<ConductorRGB> named_conductor_rgb(std::string_view metal);

// The fit behind named_conductor_rgb, for any table.
ConductorRGB fit_conductor_rgb(std::span<const OpticalConstant> table);

}  // namespace lantern
