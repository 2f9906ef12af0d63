// What a render makes of its RenderOptions: the checks that refuse options
// no render could follow, and each integrator's settings.
#pragma once

#include <cstdint>

#include "integrator/bdpt.h"
#include "integrator/metropolis.h"
#include "integrator/path_tracer.h"
#include "lantern/render.h"

namespace lantern {

// Throws std::invalid_argument, naming what is wrong.
void check_options(const Scene& scene, const RenderOptions& opt);
// Throws std::invalid_argument where what a render asks for needs the
// whole render in one process and `hooks` share it (MPI's tickets, a
// reduced film), or --part does; and for adaptive sampling that cannot
// decide (too few samples, merging).
void check_processes(const RenderOptions& opt, const RenderHooks& hooks);

// The pixels a render covers: the camera's whole image (the options'
// resolution, else the scene's), and the part of it the film holds, as
// pbrt-v4 crops: "pixelbounds" clamped to the image, else the
// "cropwindow" [x0 x1 y0 y1] as pixels ceil(W x0) to ceil(W x1) and
// ceil(H y0) to ceil(H y1). Throws std::invalid_argument when that is no
// pixel.
struct ImageRegion {
  int full_width = 0, full_height = 0;
  int x0 = 0, y0 = 0, width = 0, height = 0;
  bool cropped() const { return width != full_width || height != full_height; }
};
ImageRegion image_region(const Scene& scene, const RenderOptions& opt);

// mlt's chains: the budget in proposals (spp per pixel of the film, or
// open under a time budget) and the Integrator's parameters.
MetropolisSettings metropolis_settings(const Scene& scene, const RenderOptions& opt, const ImageRegion& region);
BdptSettings bdpt_settings(const Scene& scene, const RenderOptions& opt, const ImageRegion& region,
                           uint32_t planned_spp);
// The paths per camera sample the path tracer renders (RenderOptions::split,
// kSplitAuto for the pilot's choice; bdpt's eye subpaths alone too): 1 for
// other integrators, in scenes with media and for guided paths, whose
// field learns from the start (their pilots see them so too).
uint32_t camera_sample_split(const Scene& scene, const RenderOptions& opt);
// A guided path tracer's split once its field has learnt (pass_layout.h): what
// camera_sample_split gives the same render unguided.
uint32_t split_once_unguided(const Scene& scene, const RenderOptions& opt);
PathTracerSettings path_settings(const Scene& scene, const RenderOptions& opt, const ImageRegion& region,
                                 uint32_t planned_spp);
// The paths of each wave of a pass of one sample per pixel (vcm, bpm, ppm):
// at most wave_size, all waves of a pass the same size (a pass's last wave
// would otherwise have fewer light vertices to merge with).
uint32_t merging_wave_paths(uint32_t pixels, int wave_size);

}  // namespace lantern
