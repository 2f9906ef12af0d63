// Whether a material can scatter through a delta lobe somewhere: a smooth
// or index-matched dielectric interface, a thin dielectric, a mirror or a
// smooth conductor, a smooth coat or a smooth conductor under one. Light
// from a point, spot or distant light that scatters there first reaches
// other surfaces as a caustic only light subpaths find (an eye subpath
// cannot hit such a light, nor connect to it through a delta lobe), so the
// path tracer's kernel alone would lose it
// (integrator/eye_subpaths_alone.h).
//
// Conservative: a textured roughness or index counts as possibly smooth
// unless the texture's bounds (TexturePools::range) keep it off.
#pragma once

#include <string>

#include "material/material.h"

namespace lantern {

bool may_be_specular(const MaterialPools& materials, const TexturePools& textures, MaterialHandle m);

// pbrt-v4's name for the kind of the first of the pools' materials that may
// be specular ("dielectric", "conductor", ...), or "" where none may.
std::string kind_that_may_be_specular(const MaterialPools& materials, const TexturePools& textures);

}  // namespace lantern
