// LightSource directives and the final assembly of the scene.
#ifdef __GLIBC__
#include <malloc.h>
#endif
#include <filesystem>

#include "color/rgb_spectrum_fit.h"
#include "math/sampling.h"
#include "scene/builder.h"

namespace lantern {

using pbrt::ColorUsage;
using pbrt::ParamSet;

RGB light_scale(const ParamSet& ps) {
  const pbrt::Param* p = ps.find("scale");
  if (p && p->type != "float") return ps.get_rgb("scale", ColorUsage::Unbounded).value_or(RGB(1.f));
  return RGB(ps.get_float("scale", 1.f));
}

void SceneBuilder::light(const std::string& type, const ParamSet& ps, const Mat4& ctm, const std::string& base_dir,
                         const std::string& medium, const SourceLocation& medium_where) {
  const LightPools& L = scene_.lights;
  const size_t points = L.point.size(), spots = L.spot.size(), at_infinity = L.distant.size() + L.infinite.size();
  add_light(type, ps, ctm, base_dir);
  assign_light_media(points, spots, at_infinity, medium, medium_where);
}

void SceneBuilder::add_light(const std::string& type, const ParamSet& ps, const Mat4& ctm, const std::string& base_dir) {
  const RGB scale = light_scale(ps);
  LightPools& L = scene_.lights;
  if (type == "point") {
    RGB I = ps.get_rgb("I", ColorUsage::Illuminant).value_or(RGB(1.f)) * scale;
    if (ps.has("power")) I *= ps.get_float("power", 1.f) / (4.f * kPi);
    L.point.push_back({Vec3(ctm * Vec4(ps.get_point3("from", Vec3(0.f)), 1.f)), I, -1, {}, light_spectrum(ps, "I")});
  } else if (type == "spot") {
    RGB I = ps.get_rgb("I", ColorUsage::Illuminant).value_or(RGB(1.f)) * scale;
    Vec3 from = ps.get_point3("from", Vec3(0.f)), to = ps.get_point3("to", Vec3(0, 0, 1));
    float cone = ps.get_float("coneangle", 30.f), delta = ps.get_float("conedeltaangle", 5.f);
    if (!(cone > 0.f && cone <= 180.f)) ps.fail(*ps.find("coneangle"), "\"coneangle\" must lie in (0, 180] degrees");
    if (!(delta >= 0.f) || !std::isfinite(delta))
      ps.fail(*ps.find("conedeltaangle"), "\"conedeltaangle\" must be a finite angle of 0 degrees or more");
    float cos_end = std::cos(glm::radians(cone)), cos_start = std::cos(glm::radians(cone - delta));
    if (ps.has("power")) I *= ps.get_float("power", 1.f) / smooth_cone_mass(cos_start, cos_end);
    Vec3 axis = Vec3(ctm * Vec4(to - from, 0.f));
    if (!(glm::length(axis) > 0.f)) ps.fail("\"from\" and \"to\" must differ");
    L.spot.push_back({Vec3(ctm * Vec4(from, 1.f)), Frame::from_z(glm::normalize(axis)), I, cos_start, cos_end, {},
                      light_spectrum(ps, "I")});
  } else if (type == "distant") {
    RGB Lr = ps.get_rgb("L", ColorUsage::Illuminant).value_or(RGB(1.f)) * scale;
    if (ps.has("illuminance")) Lr *= ps.get_float("illuminance", 1.f);
    Vec3 from = ps.get_point3("from", Vec3(0.f)), to = ps.get_point3("to", Vec3(0, 0, 1));
    Vec3 w = Vec3(ctm * Vec4(from - to, 0.f));
    if (!(glm::length(w) > 0.f)) ps.fail("\"from\" and \"to\" must differ");
    L.distant.push_back({glm::normalize(w), Lr, light_spectrum(ps, "L")});
  } else if (type == "infinite") {
    InfiniteLight e;
    e.world_from_light = glm::mat3(ctm);
    e.light_from_world = glm::inverse(e.world_from_light);
    std::string file = ps.get_string("filename", ps.get_string("mapname", ""));
    auto Lc = ps.get_rgb("L", ColorUsage::Illuminant);
    // Both: a pbrt-v3 file, where L scales the map (pbrt-v4 refuses it).
    e.scale = Lc.value_or(RGB(1.f)) * scale;
    if (ps.has("portal")) {
      add_portal(e, ps, file.empty() ? file : (std::filesystem::path(base_dir) / file).string());
    } else if (!file.empty()) {
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
    if (e.image < 0 && e.portal < 0) e.spectrum = light_spectrum(ps, "L");
    L.infinite.push_back(std::move(e));
  } else if (type == "goniometric" || type == "projection") {
    profiled_light(type, ps, ctm, base_dir);
  } else {
    ps.fail("light type \"" + printable(type) + "\" is not supported; expected point, spot, goniometric, projection, "
            "distant or infinite");
  }
}

// An emitter's colour given as a spectrum ("blackbody", a "spectrum" file
// or pairs), divided by its luminance and by its colour's, so that
// emitted_spectrum (color/densely_sampled_spectrum.h) scales it by the
// luminance of the emitter's final colour, which carries "scale", "power"
// and the rest; nullopt for a colour given any other way.
std::optional<PiecewiseLinearSpectrum> SceneBuilder::emission_spectrum(const ParamSet& ps, const std::string& name) {
  if (std::optional<PiecewiseLinearSpectrum> s = color_space_emission(ps, name)) return s;
  std::optional<ParamSet::EmissionSpectrum> e = ps.get_emission_spectrum(name);
  if (!e) return std::nullopt;
  const double y = spectrum_luminance(e->spectrum) * double(luminance(e->rgb));
  if (!(y > 0.0) || !std::isfinite(y)) return std::nullopt;
  for (double& v : e->spectrum.value) v /= y;
  return std::move(e->spectrum);
}

// An emitter's RGB of rec2020, dci-p3 or aces2065-1 as pbrt-v4's
// illuminant of that space: 2m times the space's table's spectrum of
// rgb / 2m (m its largest channel), times the space's white (D65, or
// ACES's daylight) normalised to luminance 1, as RGB emitters' white is
// (color/spectrum_conversion.h). The RGB renderer's colour is the one
// ParamSet::get_rgb gives, clamped into sRGB's gamut; emitted_spectrum
// multiplies a light's spectrum by that colour's luminance (times scale,
// power and the rest), so the spectrum is divided by it here. nullopt for
// other colours, and for one whose sRGB colour is black.
std::optional<PiecewiseLinearSpectrum> SceneBuilder::color_space_emission(const ParamSet& ps, const std::string& name) {
  const pbrt::Param* p = ps.find(name);
  const ColorSpace* cs = ps.color_space;
  if (!p || !cs || cs == &ColorSpace::srgb() || !cs->illuminant || (p->type != "rgb" && p->type != "color") ||
      p->numbers.size() != 3)
    return std::nullopt;
  const RGB given(float(p->numbers[0]), float(p->numbers[1]), float(p->numbers[2]));
  const float y = luminance(ps.to_srgb(*p, given, ColorUsage::Illuminant, false));  // (get_rgb's, warned once)
  const UnboundedSpectrum u =
      unbounded_spectrum_in(color_space_table(*cs), {p->numbers[0], p->numbers[1], p->numbers[2]});
  if (!(y > 0.f) || !(u.scale > 0.f)) return std::nullopt;
  const double white = 1.0 / illuminant_luminance(cs->illuminant);
  return spectrum_every_nanometre([&](int nm) {
    return double(u.scale) * double(u.shape(float(nm))) * double(cs->illuminant(float(nm))) * white / double(y);
  });
}

// A light's: kept with the textures' spectra (light_spectrum, light/lights.h); -1 for none.
int32_t SceneBuilder::light_spectrum(const ParamSet& ps, const std::string& name) {
  std::optional<PiecewiseLinearSpectrum> s = emission_spectrum(ps, name);
  return s ? add_spectrum(*s) : -1;
}

// pbrt-v4's portal: four corners in world space, in order, around the
// window the map shines through (light/portal.h). Without a map, L (or the
// default white) makes a one-texel map.
void SceneBuilder::add_portal(InfiniteLight& e, const ParamSet& ps, const std::string& path) {
  const std::vector<Vec3> P = ps.get_point3s("portal");
  if (P.size() != 4)
    ps.fail(*ps.find("portal"), "\"portal\" has " + std::to_string(P.size()) + " points, expected the 4 corners of a rectangle");
  Vec3 corners[4];
  for (int i = 0; i < 4; ++i) corners[i] = Vec3(render_from_world_ * glm::dvec4(glm::dvec3(P[size_t(i)]), 1.0));
  TextureImage map;
  if (path.empty()) {
    map.width = map.height = 1;
    map.texels = {RGB(1.f)};
  } else {
    map = scene_.textures.images[size_t(texture_image(ps, path, ColorEncoding{ColorEncoding::SRGB}))];
    if (map.width != map.height)
      ps.fail(*ps.find("filename"), "a portal light's map must be a square equal-area image; \"" + printable(path) +
                                        "\" is " + std::to_string(map.width) + "x" + std::to_string(map.height));
  }
  try {
    scene_.lights.portals.push_back(make_portal(corners, map, e.light_from_world, e.scale));
  } catch (const std::invalid_argument& err) {
    ps.fail(*ps.find("portal"), err.what());
  }
  e.portal = int32_t(scene_.lights.portals.size() - 1);
}

// pbrt-v4's goniometric light (I times a grey equal-area image of the
// sphere, its y and z axes swapped) and projection light (scale times an
// image thrown through a frustum of "fov" degrees along +z, y flipped so
// the image's top is up), both at the origin of their space.
void SceneBuilder::profiled_light(const std::string& type, const ParamSet& ps, const Mat4& ctm, const std::string& base_dir) {
  const bool gonio = type == "goniometric";
  const std::string file = ps.get_string("filename", "");
  if (file.empty()) ps.fail("a " + type + " light needs an image: give \"string filename\"");
  IntensityProfile prof;
  prof.kind = gonio ? ProfileKind::Goniometric : ProfileKind::Projection;
  prof.image = texture_image(ps, resolve_path(base_dir, file), ColorEncoding{ColorEncoding::SRGB});
  const TextureImage& img = scene_.textures.images[size_t(prof.image)];
  glm::mat3 axes(1.f);
  RGB I = light_scale(ps);
  if (gonio) {
    if (img.width != img.height)
      ps.fail(*ps.find("filename"), "goniometric image \"" + printable(file) + "\" is " + std::to_string(img.width) + "x" +
                                        std::to_string(img.height) + ": expected a square equal-area image");
    I *= ps.get_rgb("I", ColorUsage::Illuminant).value_or(RGB(1.f));
    axes = glm::mat3(Vec3(1, 0, 0), Vec3(0, 0, 1), Vec3(0, 1, 0));
  } else {
    const float fov = ps.get_float("fov", 90.f);
    if (!(fov > 0.f && fov < 180.f)) ps.fail(*ps.find("fov"), "\"fov\" must be between 0 and 180 degrees");
    const float aspect = float(img.width) / float(img.height);
    prof.screen_hi = aspect > 1.f ? Vec2(aspect, 1.f) : Vec2(1.f, 1.f / aspect);
    prof.screen_lo = -prof.screen_hi;
    prof.tan_half = std::tan(glm::radians(fov) / 2.f);
    axes[1][1] = -1.f;
  }
  prof.world_from_light = glm::mat3(ctm) * axes;
  if (std::fabs(glm::determinant(prof.world_from_light)) < 1e-30f) ps.fail("the light's transform is singular");
  prof.light_from_world = glm::inverse(prof.world_from_light);
  if (ps.has("power")) {
    // As pbrt-v4: the power of the profile alone, whatever I is.
    const float k = profile_power(prof, scene_.textures);
    if (k > 0.f) I *= ps.get_float("power", 1.f) / k;
  }
  scene_.lights.profiles.push_back(std::move(prof));
  scene_.lights.point.push_back({Vec3(ctm * Vec4(0.f, 0.f, 0.f, 1.f)), I, int32_t(scene_.lights.profiles.size() - 1), {}});
}

// Parsing frees millions of small blocks and every file's text, and PLY
// reading its buffers; glibc keeps freed heap pages unless asked, and the
// BVH build's peak then comes on top of them (about 90 bytes per placement,
// measured; docs/performance.md, "Production scale").
static void return_free_memory() {
#ifdef __GLIBC__
  malloc_trim(0);
#endif
}

void SceneBuilder::finish() {
  check_objects_closed();
  check_lens_focus();
  finish_media();
  return_free_memory();
  load_pending_meshes();
  count_triangles();
  // Growth by doubling leaves up to half a pool unused; millions of
  // placements make that hundreds of megabytes for the whole render.
  scene_.shapes.instances.shrink_to_fit();
  return_free_memory();
  if (progress_) progress_("building the BVH");
  scene_.accel = std::make_unique<EmbreeScene>(scene_.shapes, scene_.textures, memory_layout_);
  scene_.accel->bounds(&scene_.bounds_lo, &scene_.bounds_hi);
  Vec3 center(0.f);
  float radius = 1.f;
  if (glm::all(glm::lessThanEqual(scene_.bounds_lo, scene_.bounds_hi))) {  // something is traced
    center = 0.5f * (scene_.bounds_lo + scene_.bounds_hi);
    radius = max_num(glm::length(scene_.bounds_hi - center), 1e-6f);
  }
  volume_lights();
  finalize_lights(scene_.lights, scene_.shapes, scene_.textures, center, radius);
  // (ambient occlusion needs none; its image is the sky's openness)
  if (scene_.lights.empty() && scene_.settings.integrator != Integrator::AmbientOcclusion)
    warn({}, "the scene has no lights: the image will be black");
}

}  // namespace lantern
