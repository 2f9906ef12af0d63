// What a user asks of a render on top of the scene file's own settings: the
// command line's `lantern render` options and the Python module's keyword
// arguments are both this, so that one word means one thing in each. The
// scene decides whatever the request leaves unset.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "lantern/image.h"
#include "lantern/render.h"
#include "app/provenance.h"
#include "lantern/scene.h"

namespace lantern {

struct RenderRequest {
  std::string integrator;     // empty: the scene's Integrator
  std::string sampler;        // empty: the scene's Sampler
  std::string light_sampler;  // empty: the scene's "lightsampler", else bvh
  std::string light_choice = "auto";  // RenderOptions::light_choice
  std::string mis = "power", rays = "stream";
  int spp = 0;         // 0: the scene's pixelsamples
  int maxdepth = -1;   // -1: the scene's
  int threads = 0;     // 0: all cores
  int wave_size = 0;   // 0: 4096, or 16384 for vcm, bpm, ppm (docs/vcm.md)
  double time = 0.0;   // > 0: render for this many seconds instead of a sample count
  double target_error = 0.0;  // > 0: adaptive sampling (docs/adaptive-sampling.md)
  uint64_t seed = 0;
  float vcm_radius = 0.f, vcm_alpha = 0.75f;
  float roulette = 2.f;  // path: RenderOptions::roulette_scale
  std::string split = "auto";           // path: RenderOptions::split (auto, 1, 2, 4, 8, 16)
  std::string light_subpaths = "auto";  // bdpt: RenderOptions::light_subpath_rate, "auto" or 0.01 to 1
  std::string merging = "auto";         // vcm: RenderOptions::merging_pilot, "auto" or "on"
  bool spectral = false, guide = false, guide_light = false, adaptive = false;
  std::string guide_distribution = "vmm";
  std::string guide_stop = "auto";  // RenderOptions::guide_stop: "auto" or "never"
  std::vector<int> resolution;  // empty, or W H
  // The part of the image to render (pbrt-v4's flags of these names):
  // empty, or x0 x1 y0 y1 in [0, 1] / in pixels, or a pixel's X Y.
  std::vector<float> crop_window;
  std::vector<int> pixel_bounds, pixel;
};

// The options of a render of `scene` as `request` asks. Throws
// std::invalid_argument for a word no option has (an unknown integrator, ...)
// or a region that is not one.
RenderOptions resolve_render_options(const Scene& scene, const RenderRequest& request);

// The request's render region (--cropwindow, --pixelbounds, --pixel: at most
// one) in o. Throws std::invalid_argument, saying what was expected, for
// values out of order or range.
void set_render_region(const RenderRequest& request, RenderOptions& o);

// When the request's resolution has another aspect ratio than the scene's
// Film: how the view changes (a field of view spans the image's shorter
// side, as in pbrt-v4, so the longer side sees more or less than the scene
// file's image); otherwise "".
std::string reframing_note(const Scene& scene, const RenderOptions& options);

// What a checkpoint or a part file must agree with: the scene file's name
// and bytes (FNV-1a) and what was loaded from it, so that an edited scene is
// neither resumed nor merged; for a scene given as text, the text's.
std::string scene_key(const std::string& path, const SceneInfo& info);
std::string scene_key_of_text(const std::string& name, const std::string& text, const SceneInfo& info);

// The header of a rendered image: the settings, the figures, where it came
// from (src/app/provenance.h), and a crop's place in the whole image.
ImageMetadata render_metadata(const Scene& scene, const std::string& scene_path, const RenderOptions& o,
                              const RenderResult& r, const Provenance& provenance);

}  // namespace lantern
