// pbrt-v4's coateddiffuse: a dielectric coat (smooth or GGX) over a
// Lambertian base, optionally with a scattering medium between them, as a
// layered BSDF evaluated by random walks (material/layered_bsdf.h).
#pragma once

#include "material/dielectric_bsdf.h"
#include "material/diffuse_bsdf.h"
#include "material/layered_bsdf.h"

namespace lantern {

using CoatedDiffuseBSDF = LayeredBSDF<DielectricBSDF, DiffuseBSDF>;

}  // namespace lantern
