#include "app/render_request.h"

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <stdexcept>

#include "color/color_space.h"
#include "integrator/render_settings.h"
#include "math/fnv1a.h"

namespace lantern {

RenderOptions resolve_render_options(const Scene& scene, const RenderRequest& a) {
  const SceneSettings& ss = scene_settings(scene);
  RenderOptions o;
  o.integrator = a.integrator.empty() ? ss.integrator : parse_integrator(a.integrator);
  o.vcm_radius = a.vcm_radius;
  o.vcm_alpha = a.vcm_alpha;
  o.mis = parse_mis(a.mis);
  o.spectral = a.spectral;
  o.spp = a.spp > 0 ? a.spp : ss.spp;
  o.time_limit_seconds = a.time;
  o.target_error = a.target_error;
  o.guiding = a.guide;
  if (a.target_error > 0 && a.spp == 0) o.spp = 1 << 16;  // adaptive: the limit is spp, when given
  o.maxdepth = a.maxdepth >= 0 ? a.maxdepth : ss.maxdepth;
  o.threads = a.threads;
  o.seed = a.seed;
  o.sampler = ss.sampler;
  o.light_sampler = a.light_sampler.empty() ? ss.light_sampler : parse_light_sampler(a.light_sampler);
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
  o.ray_backend = parse_ray_backend(a.rays);
  o.wave_size = a.wave_size > 0 ? a.wave_size : merges_vertices(o.integrator) ? 16384 : 4096;
  return o;
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
  add_provenance(md, provenance);
  if (const ImageRegion region = image_region(scene, o); region.cropped())
    // A crop (Film "cropwindow", "pixelbounds"): where it lies in the whole
    // image, as OpenEXR's data and display windows say it.
    md.emplace_back("pixelbounds", std::to_string(region.x0) + " " + std::to_string(region.y0) + " " +
                                       std::to_string(region.full_width) + " " + std::to_string(region.full_height));
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
