// Measured scattering coefficients that pbrt-v4's "preset" parameter names,
// in the units the papers give them (per millimetre): Jensen, Marschner,
// Levoy & Hanrahan, "A Practical Model for Subsurface Light Transport"
// (SIGGRAPH 2001), table 2, and Narasimhan, Gupta, Donner, Ramamoorthi,
// Nayar & Jensen, "Acquiring Scattering Properties of Participating Media by
// Dilution" (SIGGRAPH 2006), table 1. As in pbrt-v4, the reduced scattering
// coefficient is used as sigma_s (with the medium's own g, 0 by default).
#pragma once

#include <optional>
#include <string>

#include "math/common.h"

namespace lantern {

struct ScatteringPreset {
  RGB sigma_s, sigma_a;
};

std::optional<ScatteringPreset> medium_preset(const std::string& name);
// Every name, comma separated, for error messages.
std::string medium_preset_names();

}  // namespace lantern
