// LightSource directives and the final assembly of the scene.
#include <filesystem>

#include "scene/builder.h"

namespace lantern {

using pbrt::ColorUsage;
using pbrt::ParamSet;

RGB light_scale(const ParamSet& ps) {
  const pbrt::Param* p = ps.find("scale");
  if (p && p->type != "float") return ps.get_rgb("scale", ColorUsage::Unbounded).value_or(RGB(1.f));
  return RGB(ps.get_float("scale", 1.f));
}

void SceneBuilder::light(const std::string& type, const ParamSet& ps, const Mat4& ctm, const std::string& base_dir) {
  const RGB scale = light_scale(ps);
  LightPools& L = scene_.lights;
  if (type == "point") {
    RGB I = ps.get_rgb("I", ColorUsage::Illuminant).value_or(RGB(1.f)) * scale;
    if (ps.has("power")) I *= ps.get_float("power", 1.f) / (4.f * kPi);
    L.point.push_back({Vec3(ctm * Vec4(ps.get_point3("from", Vec3(0.f)), 1.f)), I});
  } else if (type == "spot") {
    RGB I = ps.get_rgb("I", ColorUsage::Illuminant).value_or(RGB(1.f)) * scale;
    Vec3 from = ps.get_point3("from", Vec3(0.f)), to = ps.get_point3("to", Vec3(0, 0, 1));
    float cone = ps.get_float("coneangle", 30.f), delta = ps.get_float("conedeltaangle", 5.f);
    float cos_end = std::cos(glm::radians(cone)), cos_start = std::cos(glm::radians(cone - delta));
    if (ps.has("power")) I *= ps.get_float("power", 1.f) / (2.f * kPi * ((1.f - cos_start) + (cos_start - cos_end) / 2.f));
    Vec3 axis = Vec3(ctm * Vec4(to - from, 0.f));
    if (!(glm::length(axis) > 0.f)) ps.fail("\"from\" and \"to\" must differ");
    L.spot.push_back({Vec3(ctm * Vec4(from, 1.f)), Frame::from_z(glm::normalize(axis)), I, cos_start, cos_end});
  } else if (type == "distant") {
    RGB Lr = ps.get_rgb("L", ColorUsage::Illuminant).value_or(RGB(1.f)) * scale;
    if (ps.has("illuminance")) Lr *= ps.get_float("illuminance", 1.f);
    Vec3 from = ps.get_point3("from", Vec3(0.f)), to = ps.get_point3("to", Vec3(0, 0, 1));
    Vec3 w = Vec3(ctm * Vec4(from - to, 0.f));
    if (!(glm::length(w) > 0.f)) ps.fail("\"from\" and \"to\" must differ");
    L.distant.push_back({glm::normalize(w), Lr});
  } else if (type == "infinite") {
    InfiniteLight e;
    e.world_from_light = glm::mat3(ctm);
    e.light_from_world = glm::inverse(e.world_from_light);
    std::string file = ps.get_string("filename", ps.get_string("mapname", ""));
    auto Lc = ps.get_rgb("L", ColorUsage::Illuminant);
    // Both: a pbrt-v3 file, where L scales the map (pbrt-v4 refuses it).
    e.scale = Lc.value_or(RGB(1.f)) * scale;
    if (!file.empty()) {
      TextureImage img = load_texture_image((std::filesystem::path(base_dir) / file).string(), ColorEncoding{ColorEncoding::SRGB});
      if (img.width == img.height) {
        e.equal_area = true;
      } else if (img.width == 2 * img.height) {
        e.equal_area = false;
        warn(ps.where, "environment map \"" + printable(file) + "\" is not square: read as latitude-longitude (pbrt-v3 layout)");
      } else {
        ps.fail("environment map \"" + printable(file) + "\" is " + std::to_string(img.width) + "x" + std::to_string(img.height) +
                ": expected a square equal-area image (pbrt-v4) or a 2:1 latitude-longitude one");
      }
      e.image = int32_t(scene_.textures.images.size());
      scene_.textures.images.push_back(std::move(img));
    }
    L.infinite.push_back(std::move(e));
  } else {
    ps.fail("light type \"" + printable(type) + "\" is not supported; expected point, spot, distant or infinite");
  }
}

void SceneBuilder::finish() {
  check_objects_closed();
  load_pending_meshes();
  count_triangles();
  if (progress_) progress_("building the BVH");
  scene_.accel = std::make_unique<EmbreeScene>(scene_.shapes, scene_.textures);
  scene_.accel->bounds(&scene_.bounds_lo, &scene_.bounds_hi);
  Vec3 center(0.f);
  float radius = 1.f;
  if (glm::all(glm::lessThanEqual(scene_.bounds_lo, scene_.bounds_hi))) {  // something is traced
    center = 0.5f * (scene_.bounds_lo + scene_.bounds_hi);
    radius = std::fmax(glm::length(scene_.bounds_hi - center), 1e-6f);
  }
  finalize_lights(scene_.lights, scene_.shapes, scene_.textures, center, radius);
  if (scene_.lights.empty()) warn({}, "the scene has no lights: the image will be black");
}

}  // namespace lantern
