// pbrt-v4's coatedconductor: a dielectric coat (smooth or GGX) over a
// conductor (smooth or GGX, complex Fresnel relative to the coat), with an
// optional scattering medium between them, as a layered BSDF evaluated by
// random walks (material/layered_bsdf.h).
#pragma once

#include "material/conductor_bsdf.h"
#include "material/dielectric_bsdf.h"
#include "material/layered_bsdf.h"

namespace lantern {

using CoatedConductorBSDF = LayeredBSDF<DielectricBSDF, ConductorBSDF>;

}  // namespace lantern
