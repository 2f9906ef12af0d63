// Loading a scene in pbrt-v4 format.
#pragma once

#include "lantern/options.h"
#include <array>
#include <limits>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>

#include "lantern/error.h"

namespace lantern {

struct Scene;  // entities and component pools; see src/scene/scene.h

// What the scene file asks for; the command line may override each.
// The scene's Sampler: pbrt-v4's types, parameters and defaults
// (docs/samplers.md).
struct SamplerSettings {
  SamplerKind type = SamplerKind::ZSobol;
  std::string randomization;    // fastowen, owen, permutedigits, none; empty: the type's default
  uint64_t seed = 0;
  int xsamples = 4, ysamples = 4;  // stratified
  bool jitter = true;              // stratified
};

struct SceneSettings {
  Integrator integrator = Integrator::Path;
  int maxdepth = 5;
  int spp = 16;
  int width = 1280, height = 720;
  std::string output = "pbrt.exr";
  SamplerSettings sampler;
  // The Integrator's "lightsampler" (pbrt-v4's names; bvh by default).
  LightSamplerKind light_sampler = LightSamplerKind::Bvh;
  // An "sppm" Integrator's "radius": vcm's first merging radius (0: automatic).
  float merge_radius = 0.f;
  // An "sppm" Integrator's "photonsperiteration": the light subpaths each
  // eye vertex merges with, per pass; -1 (pbrt-v4's default) a pass's
  // pixels. 0 when the scene asks for no photon mapping (its vcm keeps
  // waves of the default size: docs/vcm.md, "Light subpaths per merge").
  int64_t photons_per_iteration = 0;
  // An "ambientocclusion" Integrator's "maxdistance" (what lies farther
  // does not occlude) and "cossample" (directions drawn by the cosine, or
  // uniformly over the hemisphere): pbrt-v4's defaults.
  float ao_max_distance = std::numeric_limits<float>::infinity();
  bool ao_cos_sample = true;
  // An "mlt" Integrator's parameters, pbrt-v4's names and defaults:
  // "mutationsperpixel" (the render's samples per pixel unless --spp or
  // --time says otherwise), "chains", "bootstrapsamples",
  // "largestepprobability", "sigma".
  int mlt_mutations_per_pixel = 100;
  int mlt_chains = 1000;
  int mlt_bootstrap_samples = 100000;
  float mlt_large_step_probability = 0.3f, mlt_sigma = 0.01f;
  // A material's index varies with wavelength: it disperses light with
  // sampled wavelengths (RenderOptions::spectral) only.
  bool dispersive = false;
  // pbrt-v4's film sensor (its "cie1931" one): Film "iso" and
  // "whitebalance" (kelvin, 0: none), and the Camera's shutter interval,
  // whose product with iso / 100 scales the image.
  float iso = 100.f, whitebalance = 0.f, exposure_time = 1.f;
  // Film "maxcomponentvalue": a sample whose largest component in the
  // sensor's RGB (for "cie1931", XYZ times the imaging ratio) is above it
  // is scaled down to it, as pbrt-v4's RGB film does (infinite: never).
  float max_component_value = std::numeric_limits<float>::infinity();
  // Film "savefp16": an OpenEXR output of 16-bit floats. pbrt-v4 writes
  // them unless told otherwise; Lantern keeps 32 bits unless the Film asks,
  // since 16 bits round to 1/2048 of a value and end at 65504.
  bool save_fp16 = false;
  // Film "gbuffer": the image carries pbrt-v4's gbuffer channels
  // (RenderOptions::gbuffer), in camera space or, with "coordinatesystem"
  // "world", the world's.
  bool gbuffer = false, gbuffer_world = false;
  // Film "spectral": "nbuckets" (0 for other films), "lambdamin",
  // "lambdamax" (RenderOptions::spectral_buckets).
  int spectral_buckets = 0;
  float spectral_lambda_min = 360.f, spectral_lambda_max = 830.f;
  // The image's colour space: the ColorSpace in effect at Film (pbrt-v4's
  // names: srgb, rec2020, dci-p3, aces2065-1). The renderer's colours are
  // linear sRGB; the sensor converts.
  std::string color_space = "srgb";
  // The part of the image rendered (pbrt-v4's Film "cropwindow", x0 x1 y0
  // y1 in [0, 1], and "pixelbounds", in pixels; x1 < 0: not given). The
  // render's resolution decides the pixels a crop window covers.
  std::array<float, 4> crop_window{0.f, 1.f, 0.f, 1.f};
  std::array<int, 4> pixel_bounds{0, -1, 0, -1};
  // The Camera's view does not follow the image's shape (it gave a
  // "screenwindow", or it is spherical): another resolution stretches the
  // image rather than reframing it.
  bool screen_window = false;
};

struct LoadOptions {
  WarningSink warn;  // receives "file:line:col: warning: ..." lines
  std::function<void(const std::string&)> progress;  // receives the stage being entered ("reading 25 PLY meshes", ...)
  // receives each included scene file, with its size, as parsing reaches it
  std::function<void(const std::string& path, size_t bytes)> file_progress;
  // Image textures are read through a tile cache of at most this size, from
  // tiled, MIP-mapped files prepared into texture_directory (empty: the
  // user's cache folder) when the scene's own are not (docs/textures.md).
  double texture_cache_mb = 1024.0;
  std::string texture_directory;
  // load_scene_from_string: where the text's relative file names (Include,
  // PLY meshes, images) resolve (empty: the working directory).
  std::string base_directory;
  // A parameter neither pbrt-v4 nor pbrt-v3 reads (a typo, most often) is
  // an error, as in pbrt-v4; lenient makes it a warning (--lenient).
  bool lenient = false;
  // Fast or compact acceleration structures (lantern/options.h).
  MemoryLayout memory_layout = MemoryLayout::Auto;
  // Threads for loading (Import'ed files, PLY meshes, the BVH); 0: as many
  // as oneTBB may use. The scene is the same whatever the count.
  int threads = 0;
};

// Throws InputError for anything wrong with the input.
std::shared_ptr<Scene> load_scene(const std::string& path, const LoadOptions& options = {});
std::shared_ptr<Scene> load_scene_from_string(const std::string& text, const std::string& filename_for_messages,
                                              const LoadOptions& options = {});
const SceneSettings& scene_settings(const Scene& scene);

// What a loaded scene holds and what building it cost.
struct SceneInfo {
  size_t triangles = 0, spheres = 0, lights = 0;  // stored once each
  size_t bilinear_patches = 0;     // quads that are not parallelograms, stored once each
  size_t curve_segments = 0;       // cubic segments, stored once each
  size_t instances = 0;            // ObjectInstance placements
  size_t instanced_triangles = 0;  // triangles as traced: outside objects once, inside once per instance
  double bvh_build_seconds = 0.0;
  int64_t bvh_bytes = 0;        // Embree's own memory after the build
  int64_t bvh_peak_bytes = 0;   // including the builder's temporaries
  bool compact_instances = false, compact_bvh = false;  // the memory layout chosen
  size_t geometry_bytes = 0;    // the scene's vertex, index, normal and uv pools, patches, curves, placements
};
SceneInfo scene_info(const Scene& scene);

}  // namespace lantern
