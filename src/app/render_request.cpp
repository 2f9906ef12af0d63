#include "app/render_request.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <stdexcept>

#include "color/color_space.h"
#include "integrator/render_settings.h"
#include "math/fnv1a.h"

namespace lantern {

// --cropwindow, --pixelbounds, --pixel: at most one of them, each a region
// of at least one pixel (a crop window's values in [0, 1]).
void set_render_region(const RenderRequest& a, RenderOptions& o) {
  const int given = int(!a.crop_window.empty()) + int(!a.pixel_bounds.empty()) + int(!a.pixel.empty());
  if (given > 1) throw std::invalid_argument("give one render region: --cropwindow, --pixelbounds or --pixel");
  if (!a.crop_window.empty()) {
    const std::vector<float>& c = a.crop_window;
    if (c.size() != 4 || !std::all_of(c.begin(), c.end(), [](float v) { return v >= 0.f && v <= 1.f; }) ||
        !(c[0] < c[1]) || !(c[2] < c[3]))
      throw std::invalid_argument("cropwindow: expected x0 x1 y0 y1 in [0, 1] with x0 < x1 and y0 < y1 (pixels: "
                                  "--pixelbounds)");
    std::copy(c.begin(), c.end(), o.crop_window.begin());
  } else if (!a.pixel_bounds.empty()) {
    const std::vector<int>& b = a.pixel_bounds;
    if (b.size() != 4 || b[0] < 0 || b[2] < 0 || b[0] >= b[1] || b[2] >= b[3])
      throw std::invalid_argument("pixelbounds: expected x0 x1 y0 y1 in pixels with 0 <= x0 < x1 and 0 <= y0 < y1");
    std::copy(b.begin(), b.end(), o.pixel_bounds.begin());
  } else if (!a.pixel.empty()) {
    if (a.pixel.size() != 2 || a.pixel[0] < 0 || a.pixel[1] < 0 || a.pixel[0] > 65535 || a.pixel[1] > 65535)
      throw std::invalid_argument("pixel: expected X Y, a pixel of the image (0 0 is the top left)");
    o.pixel_bounds = {a.pixel[0], a.pixel[0] + 1, a.pixel[1], a.pixel[1] + 1};
  }
}

RenderOptions resolve_render_options(const Scene& scene, const RenderRequest& a) {
  const SceneSettings& ss = scene_settings(scene);
  RenderOptions o;
  o.integrator = a.integrator.empty() ? ss.integrator : parse_integrator(a.integrator);
  o.vcm_radius = a.vcm_radius;
  o.vcm_alpha = a.vcm_alpha;
  o.roulette_scale = a.roulette;
  o.split = parse_split(a.split);
  o.light_subpath_rate = parse_light_subpaths(a.light_subpaths);
  o.merging_pilot = a.merging != "on";
  o.mis = parse_mis(a.mis);
  o.spectral = a.spectral;
  o.gbuffer = ss.gbuffer;
  o.gbuffer_world = ss.gbuffer_world;
  // Film "spectral" renders spectrally, as all of pbrt-v4 does.
  o.spectral_buckets = ss.spectral_buckets;
  o.spectral_lambda_min = ss.spectral_lambda_min, o.spectral_lambda_max = ss.spectral_lambda_max;
  if (o.spectral_buckets > 0) o.spectral = true;
  // mlt's budget is its Integrator's mutations per pixel, as in pbrt-v4.
  o.spp = a.spp > 0 ? a.spp : o.integrator == Integrator::Mlt ? ss.mlt_mutations_per_pixel : ss.spp;
  o.time_limit_seconds = a.time;
  o.target_error = a.target_error;
  o.guiding = a.guide;
  o.guide_light_subpaths = a.guide_light;
  o.guide_distribution = parse_guide_model(a.guide_distribution);
  if (a.guide_stop != "auto" && a.guide_stop != "never")
    throw std::invalid_argument("--guide-stop: expected auto or never, got '" + a.guide_stop + "'");
  o.guide_stop = a.guide_stop == "auto";
  o.adaptive = a.adaptive;
  if (a.target_error > 0 && a.spp == 0) o.spp = 1 << 16;  // adaptive: the limit is spp, when given
  o.maxdepth = a.maxdepth >= 0 ? a.maxdepth : ss.maxdepth;
  o.threads = a.threads;
  o.seed = a.seed;
  o.sampler = ss.sampler;
  o.light_sampler = a.light_sampler.empty() ? ss.light_sampler : parse_light_sampler(a.light_sampler);
  o.light_choice = parse_light_choice(a.light_choice);
  if (!a.sampler.empty() && parse_sampler(a.sampler) != ss.sampler.type) {
    o.sampler = SamplerSettings{};  // the scene's parameters belong to its own type
    o.sampler.type = parse_sampler(a.sampler);
    o.sampler.seed = ss.sampler.seed;
  }
  if (!a.resolution.empty()) {
    if (a.resolution.size() != 2 || a.resolution[0] < 1 || a.resolution[1] < 1 || a.resolution[0] > 65536 ||
        a.resolution[1] > 65536)
      throw std::invalid_argument("resolution: expected a width and a height from 1 to 65536");
    o.width = a.resolution[0];
    o.height = a.resolution[1];
  }
  set_render_region(a, o);
  o.ray_backend = parse_ray_backend(a.rays);
  o.wave_size = a.wave_size > 0 ? a.wave_size : default_wave_size(o.integrator, ss.photons_per_iteration);
  return o;
}

std::string reframing_note(const Scene& scene, const RenderOptions& o) {
  const SceneSettings& ss = scene_settings(scene);
  if (o.width <= 0 || o.height <= 0 || ss.width <= 0 || ss.height <= 0) return {};
  const double was = double(ss.width) / double(ss.height), is = double(o.width) / double(o.height);
  if (std::abs(is / was - 1.0) < 1e-3) return {};
  // pbrt-v4's screen window: [-aspect, aspect] x [-1, 1] for a wide image,
  // [-1, 1] x [-1/aspect, 1/aspect] for a tall one, so "fov" spans the
  // shorter side; a "screenwindow" given in the file is kept as it is.
  const char* how = "";
  if (ss.screen_window)
    how = "the camera's view is fixed (a \"screenwindow\", or a spherical camera), so the image is stretched";
  else if ((is > 1.0) != (was > 1.0) && std::abs(is - 1.0) > 1e-3 && std::abs(was - 1.0) > 1e-3)
    how = "the camera's view spans the shorter side, which is now the other one: the image shows more of the scene "
          "along one side and less along the other";
  else if (std::max(is, 1.0 / is) > std::max(was, 1.0 / was))
    how = "the camera's view spans the shorter side, so the image shows more of the scene along its longer side";
  else
    how = "the camera's view spans the shorter side, so the image shows less of the scene along its longer side";
  char buf[400];
  std::snprintf(buf, sizeof buf, "--resolution %dx%d has aspect ratio %.3g where the scene's Film (%dx%d) has %.3g: %s",
                o.width, o.height, is, ss.width, ss.height, was, how);
  return buf;
}

namespace {
std::string key_of(const std::string& name, const Fnv1a& hash, const SceneInfo& info) {
  char hex[17];
  std::snprintf(hex, sizeof hex, "%016llx", (unsigned long long)hash.h);
  return name + " " + hex + " triangles " + std::to_string(info.triangles) + " spheres " +
         std::to_string(info.spheres) + " lights " + std::to_string(info.lights);
}
}  // namespace

std::string scene_key(const std::string& path, const SceneInfo& info) {
  std::ifstream in(path, std::ios::binary);
  Fnv1a hash;
  char buf[1 << 16];
  while (in.read(buf, sizeof buf) || in.gcount() > 0) hash.add(buf, size_t(in.gcount()));
  return key_of(std::filesystem::path(path).filename().string(), hash, info);
}

std::string scene_key_of_text(const std::string& name, const std::string& text, const SceneInfo& info) {
  Fnv1a hash;
  hash.add(text.data(), text.size());
  return key_of(name, hash, info);
}

ImageMetadata render_metadata(const Scene& scene, const std::string& scene_path, const RenderOptions& o,
                              const RenderResult& r, const Provenance& provenance) {
  ImageMetadata md = {{"lantern:integrator", name(o.integrator)},
                      {"lantern:colour", o.spectral ? "spectral" : "rgb"},
                      {"lantern:spp", std::to_string(r.stats.min_spp)},
                      {"lantern:samples", std::to_string(r.stats.samples)},
                      {"lantern:seed", std::to_string(o.seed)},
                      {"lantern:maxdepth", std::to_string(o.maxdepth)},
                      {"lantern:render_seconds", std::to_string(r.total_render_seconds)},
                      {"lantern:resumed_samples", std::to_string(r.resumed_samples)},
                      {"lantern:interrupted", r.interrupted ? "true" : "false"},
                      {"lantern:scene", scene_path}};
  add_render_settings(md, o);
  if (r.stats.light_subpath_rate >= 0.f)  // bdpt: the rate used (the pilot's choice under auto)
    md.emplace_back("lantern:light_subpath_rate", exact_text(r.stats.light_subpath_rate));
  if (r.stats.merging_pilot >= 0)  // vcm: merged, or rendered as bdpt (its waves then bdpt's default)
    md.emplace_back("lantern:merging", r.stats.merging_pilot == 1 ? "merges" : "rendered as bdpt");
  add_provenance(md, provenance);
  if (const ImageRegion region = image_region(scene, o); region.cropped())
    // A crop (Film "cropwindow", "pixelbounds"): where it lies in the whole
    // image, as OpenEXR's data and display windows say it.
    md.emplace_back("pixelbounds", std::to_string(region.x0) + " " + std::to_string(region.y0) + " " +
                                       std::to_string(region.full_width) + " " + std::to_string(region.full_height));
  if (scene_settings(scene).save_fp16) md.emplace_back("half", "true");  // Film "savefp16"
  if (o.spectral_buckets > 0) {  // the OpenEXR spectral layout's attributes, as pbrt-v4 writes them
    md.emplace_back("spectralLayoutVersion", "1.0");
    md.emplace_back("emissiveUnits", "W.m^-2.sr^-1");
  }
  if (const ColorSpace* cs = ColorSpace::named(scene_settings(scene).color_space); cs && cs != &ColorSpace::srgb()) {
    // The image is in another colour space (ColorSpace before Film): say so
    // as OpenEXR does.
    std::string c;
    for (float v : chromaticities(*cs)) c += (c.empty() ? "" : " ") + std::to_string(v);
    md.emplace_back("chromaticities", c);
  }
  return md;
}

}  // namespace lantern
