// MakeNamedMedium, and the media of shapes, lights and the camera
// (pbrt's MediumInterface, read from the graphics state at each use).
#include "medium/presets.h"
#include "scene/builder.h"

namespace lantern {

using pbrt::ColorUsage;
using pbrt::ParamSet;

namespace {

RGB checked_coefficient(const ParamSet& ps, const char* name, RGB value, float scale) {
  RGB v = value * scale;
  if (!is_finite(v) || v.x < 0.f || v.y < 0.f || v.z < 0.f) {
    std::string what = std::string("\"") + name + "\" times \"scale\" must be finite and not negative";
    if (const pbrt::Param* p = ps.find(name)) ps.fail(*p, what);
    ps.fail(what);
  }
  return v;
}

}  // namespace

void SceneBuilder::medium(const std::string& name, const ParamSet& ps) {
  if (named_media_.count(name)) ps.fail("medium \"" + printable(name) + "\" is defined twice");
  const std::string type = ps.get_string("type", "");
  if (type.empty()) ps.fail("needs a \"string type\" parameter (homogeneous)");
  if (type == "uniformgrid" || type == "rgbgrid" || type == "cloud" || type == "nanovdb")
    ps.fail("medium type \"" + type + "\" is not supported yet; expected \"homogeneous\"");
  if (type != "homogeneous") ps.fail("unknown medium type \"" + printable(type) + "\"; expected \"homogeneous\"");

  RGB sigma_a(1.f), sigma_s(1.f);  // pbrt-v4's defaults
  const std::string preset = ps.get_string("preset", "");
  if (!preset.empty()) {
    auto p = medium_preset(preset);
    if (!p) ps.fail(*ps.find("preset"), "unknown preset \"" + printable(preset) + "\"; known: " + medium_preset_names());
    sigma_a = p->sigma_a;
    sigma_s = p->sigma_s;
  }
  // As in pbrt-v4, a preset wins over explicit coefficients.
  if (preset.empty()) {
    sigma_a = ps.get_rgb("sigma_a", ColorUsage::Unbounded).value_or(sigma_a);
    sigma_s = ps.get_rgb("sigma_s", ColorUsage::Unbounded).value_or(sigma_s);
  } else {
    for (const char* p : {"sigma_a", "sigma_s"}) ps.find(p);
  }
  const float scale = ps.get_float("scale", 1.f);
  HomogeneousMedium m;
  m.sigma_a = checked_coefficient(ps, "sigma_a", sigma_a, scale);
  m.sigma_s = checked_coefficient(ps, "sigma_s", sigma_s, scale);
  m.g = ps.get_float("g", 0.f);
  if (!(m.g > -1.f && m.g < 1.f)) ps.fail(*ps.find("g"), "\"g\" must lie strictly between -1 and 1");
  if (auto Le = ps.get_rgb("Le", ColorUsage::Illuminant); Le && !is_black(*Le))
    ps.fail(*ps.find("Le"), "emissive media (\"Le\") are not supported yet");
  ps.find("Lescale");
  scene_.media.homogeneous.push_back(m);
  named_media_[name] = MediumHandle::homogeneous(uint32_t(scene_.media.homogeneous.size() - 1));
}

MediumHandle SceneBuilder::find_medium(const std::string& name, const SourceLocation& where) const {
  if (name.empty()) return {};
  auto it = named_media_.find(name);
  if (it == named_media_.end())
    throw InputError(where, "medium \"" + printable(name) + "\" is not defined (MakeNamedMedium must come before its use)");
  return it->second;
}

MediumInterface SceneBuilder::medium_interface(const GraphicsState& gs) const {
  return {find_medium(gs.inside_medium, gs.medium_where), find_medium(gs.outside_medium, gs.medium_where)};
}

void SceneBuilder::camera_medium(const std::string& name, const SourceLocation& where) {
  camera_medium_ = name;
  camera_medium_where_ = where;
}

// Shapes [first, end) take the graphics state's media. A shape of the
// "interface" material that is a transition stays in the scene as a
// boundary the integrators cross; any other one has no effect and is cut
// out (SceneBuilder::shape).
void SceneBuilder::assign_media(size_t first, const GraphicsState& gs) {
  MediumInterface mi = medium_interface(gs);
  for (size_t g = first; g < scene_.shapes.geometries.size(); ++g) scene_.shapes.geometries[g].media = mi;
}

// Lights added since the counts were taken are in the graphics state's
// outside medium, as in pbrt-v4.
void SceneBuilder::assign_light_media(size_t points, size_t spots, size_t at_infinity, const std::string& name,
                                      const SourceLocation& where) {
  MediumHandle m = find_medium(name, where);
  LightPools& L = scene_.lights;
  for (size_t i = points; i < L.point.size(); ++i) L.point[i].medium = m;
  for (size_t i = spots; i < L.spot.size(); ++i) L.spot[i].medium = m;
  if (!m.vacuum() && L.distant.size() + L.infinite.size() > at_infinity)
    warn(where, "a light at infinity emits into vacuum here, not into medium \"" + printable(name) +
                    "\": bound the medium by a shape with a MediumInterface (docs/media.md)");
}

void SceneBuilder::finish_media() {
  scene_.media.camera = find_medium(camera_medium_, camera_medium_where_);
}

}  // namespace lantern
