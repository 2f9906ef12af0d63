// What a render makes of its RenderOptions: the checks that refuse options
// no render could follow, and each integrator's settings.
#pragma once

#include <cstdint>

#include "integrator/bdpt.h"
#include "integrator/path_tracer.h"
#include "lantern/render.h"

namespace lantern {

// Throws std::invalid_argument, naming what is wrong.
void check_options(const Scene& scene, const RenderOptions& opt);
BdptSettings bdpt_settings(const Scene& scene, const RenderOptions& opt, int width, int height, uint32_t planned_spp);
PathTracerSettings path_settings(const Scene& scene, const RenderOptions& opt, int width, int height,
                                 uint32_t planned_spp);

}  // namespace lantern
