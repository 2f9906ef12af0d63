// The Texture directive and texture-valued parameters, with pbrt-v4's
// classes, parameter names and defaults. Float and spectrum textures have
// separate names, as in pbrt-v4.
#include <glm/gtc/matrix_inverse.hpp>

#include "scene/builder.h"

#include <algorithm>
#include <cstdio>

#include "color/rgb_spectrum_fit.h"

namespace lantern {

using pbrt::ColorUsage;
using pbrt::ParamSet;

RGBTextureRef SceneBuilder::rgb_texture(const ParamSet& ps, const std::string& name, RGB def, ColorUsage usage) {
  if (auto tex = ps.get_texture(name)) {
    if (auto it = rgb_textures_.find(*tex); it != rgb_textures_.end()) return it->second;
    if (float_textures_.count(*tex))
      ps.fail(*ps.find(name), "\"" + printable(*tex) + "\" is a float texture; \"" + name + "\" needs a spectrum texture");
    ps.fail(*ps.find(name), "no spectrum texture named \"" + printable(*tex) + "\" was defined");
  }
  if (const pbrt::Param* p = ps.find(name); p && p->type == "float")
    return RGBTextureRef::constant(RGB(ps.get_float(name, 0.f)));
  RGBTextureRef ref = RGBTextureRef::constant(ps.get_rgb(name, usage).value_or(def));
  // A spectrum given by samples is kept for the spectral renderer too
  // (emitters' spectra are the lights' to keep).
  if (usage != ColorUsage::Illuminant) {
    if (auto sampled = ps.get_sampled_spectrum(name)) ref.spectrum = add_spectrum(*sampled);
    else if (const pbrt::Param* p = ps.find(name)) ref.spectrum = color_space_spectrum(ps, *p, usage);
  }
  return ref;
}

LazyRGBToSpectrumTable& SceneBuilder::color_space_table(const ColorSpace& cs) {
  std::unique_ptr<LazyRGBToSpectrumTable>& table = color_space_tables_[std::string(cs.name)];
  if (!table) table = std::make_unique<LazyRGBToSpectrumTable>(cs);
  return *table;
}

// pbrt-v4 turns an RGB of any colour space into a spectrum by that space's
// own table. The build fits sRGB's only, and the RGB renderer works in
// sRGB, so a colour of another space is converted into sRGB as it is read
// (clamped into its gamut, ParamSet::get_rgb); for the spectral renderer,
// a reflectance or unbounded colour of another space (rec2020, dci-p3,
// aces2065-1) is fitted here in its own space, under its own white,
// exactly as that space's table would hold it, and kept as a spectrum like
// one given by samples: colours outside sRGB's gamut keep their
// saturation.
std::optional<UnboundedSpectrum> SceneBuilder::color_space_shape(const ParamSet& ps, const pbrt::Param& p,
                                                                 ColorUsage usage) {
  const ColorSpace* cs = ps.color_space;
  if (!cs || cs == &ColorSpace::srgb() || !cs->illuminant || (p.type != "rgb" && p.type != "color") ||
      p.numbers.size() != 3)
    return std::nullopt;
  std::array<double, 3> rgb{p.numbers[0], p.numbers[1], p.numbers[2]};
  if (usage != ColorUsage::Reflectance) {
    const UnboundedSpectrum u = unbounded_spectrum_in(color_space_table(*cs), rgb);
    return u.scale > 0.f ? std::optional(u) : std::nullopt;
  }
  for (double& c : rgb) c = std::clamp(c, 0.0, 1.0);  // a reflectance: clamped into [0, 1], as pbrt-v4 clamps it
  UnboundedSpectrum u;
  u.shape = color_space_table(*cs)(RGB(float(rgb[0]), float(rgb[1]), float(rgb[2])));
  u.scale = 1.f;
  return u;
}

int32_t SceneBuilder::color_space_spectrum(const ParamSet& ps, const pbrt::Param& p, ColorUsage usage) {
  const std::optional<UnboundedSpectrum> u = color_space_shape(ps, p, usage);
  if (!u) return -1;
  char key[160];  // (exact: the polynomial's and the scale's bits in hexadecimal)
  std::snprintf(key, sizeof key, "%.*s %a %a %a %a", int(ps.color_space->name.size()), ps.color_space->name.data(),
                double(u->shape.c0), double(u->shape.c1), double(u->shape.c2), double(u->scale));
  if (auto it = color_space_spectra_.find(key); it != color_space_spectra_.end()) return it->second;
  return color_space_spectra_[key] = add_spectrum(
             spectrum_every_nanometre([&](int nm) { return double(u->scale) * double(u->shape(float(nm))); }));
}

int32_t SceneBuilder::add_spectrum(const PiecewiseLinearSpectrum& s) {
  scene_.textures.spectra.emplace_back(s);
  return int32_t(scene_.textures.spectra.size() - 1);
}

FloatTextureRef SceneBuilder::float_texture(const ParamSet& ps, const std::string& name, float def) {
  if (auto tex = ps.get_texture(name)) {
    if (auto it = float_textures_.find(*tex); it != float_textures_.end()) return it->second;
    if (rgb_textures_.count(*tex))
      ps.fail(*ps.find(name), "\"" + printable(*tex) + "\" is a spectrum texture; \"" + name + "\" needs a float texture");
    ps.fail(*ps.find(name), "no float texture named \"" + printable(*tex) + "\" was defined");
  }
  float v = ps.get_float(name, def);
  if (!std::isfinite(v)) ps.fail(*ps.find(name), "must be finite");
  return FloatTextureRef::constant(v);
}

RGBTextureRef SceneBuilder::add_texture_node(TextureNode n) {
  // Kinds with children: spectral where a child holds a spectrum.
  const bool parent = n.kind == TextureKind::Checkerboard || n.kind == TextureKind::Dots ||
                      n.kind == TextureKind::Scale || n.kind == TextureKind::Mix || n.kind == TextureKind::DirectionMix;
  auto spectral = [&](const RGBTextureRef& r) {
    return r.spectrum >= 0 || (r.node >= 0 && scene_.textures.nodes[size_t(r.node)].spectral);
  };
  n.spectral = parent && !n.is_float && (spectral(n.tex1) || (n.kind != TextureKind::Scale && spectral(n.tex2)));
  scene_.textures.nodes.push_back(std::move(n));
  return RGBTextureRef{RGB(0.f), int32_t(scene_.textures.nodes.size() - 1), -1};
}

TextureMapping SceneBuilder::texture_mapping(const ParamSet& ps, const Mat4& ctm, bool two_d) {
  TextureMapping m;
  std::string kind = two_d ? ps.get_string("mapping", "uv") : "point";
  if (kind != "uv") {
    if (!(std::fabs(glm::determinant(ctm)) > 0.f)) ps.fail("the texture's transform is singular");
    m.texture_from_world = glm::inverse(ctm);
  }
  if (kind == "uv") {
    m.kind = TextureMapping::UV;
    m.su = ps.get_float("uscale", 1.f);
    m.sv = ps.get_float("vscale", 1.f);
    m.du = ps.get_float("udelta", 0.f);
    m.dv = ps.get_float("vdelta", 0.f);
  } else if (kind == "spherical") {
    m.kind = TextureMapping::Spherical;
  } else if (kind == "cylindrical") {
    m.kind = TextureMapping::Cylindrical;
  } else if (kind == "planar") {
    m.kind = TextureMapping::Planar;
    m.v1 = ps.get_point3("v1", Vec3(1, 0, 0));
    m.v2 = ps.get_point3("v2", Vec3(0, 1, 0));
    m.du = ps.get_float("udelta", 0.f);
    m.dv = ps.get_float("vdelta", 0.f);
  } else if (kind != "point") {
    ps.fail(*ps.find("mapping"), "texture mapping \"" + printable(kind) +
                                     "\" is unknown; expected uv, spherical, cylindrical or planar");
  }
  return m;
}

// Images are read (or prepared) once per file and encoding.
static std::string image_key(const std::string& path, ColorEncoding encoding) {
  return std::to_string(int(encoding.kind)) + "/" + std::to_string(encoding.gamma) + "|" + path;
}

int32_t SceneBuilder::texture_image(const ParamSet& ps, const std::string& path, ColorEncoding encoding,
                                    const char* param) {
  const std::string key = image_key(path, encoding);
  if (auto it = images_.find(key); it != images_.end()) return it->second;
  TextureImage img;
  try {
    img = load_texture_image(path, encoding);
  } catch (const InputError& e) {
    ps.fail(*ps.find(param), e.what());
  }
  scene_.textures.images.push_back(std::move(img));
  int32_t index = int32_t(scene_.textures.images.size() - 1);
  images_[key] = index;
  return index;
}

bool SceneBuilder::resident_fits(const ParamSet& ps, const std::string& path, ColorEncoding encoding,
                                 ImageFilter filter) {
  if (filter != ImageFilter::Point && filter != ImageFilter::Bilinear) return false;
  if (images_.count(image_key(path, encoding))) return true;  // already resident, already counted
  std::pair<int, int> size;
  try {
    size = image_resolution(path);
  } catch (const InputError& e) {
    ps.fail(*ps.find("filename"), e.what());
  }
  const int64_t texels = int64_t(size.first) * size.second;
  if (texels > kMaxResidentTexels || resident_texels_ + texels > kResidentTexelBudget) return false;
  resident_texels_ += texels;
  return true;
}

int32_t SceneBuilder::cached_texture(const ParamSet& ps, const std::string& path, ColorEncoding encoding,
                                     const TextureNode& n, const char* param) {
  TexturePools& pools = scene_.textures;
  if (!pools.cache) pools.cache = std::make_shared<TextureCache>(texture_cache_);
  const std::string key = image_key(path, encoding);
  auto it = prepared_.find(key);
  if (it == prepared_.end()) {
    try {
      it = prepared_.emplace(key, prepare_texture(path, encoding, pools.cache->settings().directory)).first;
      if (it->second.converted && progress_) progress_("prepared texture " + path);
    } catch (const InputError& e) {
      ps.fail(*ps.find(param), e.what());
    }
  }
  try {
    return pools.cache->add(it->second, n.filter, n.wrap, n.max_anisotropy);
  } catch (const InputError& e) {
    ps.fail(*ps.find(param), e.what());
  }
}

static ColorEncoding parse_encoding(const ParamSet& ps, const std::string& file) {
  const pbrt::Param* p = ps.find("encoding");
  if (!p && ps.has("gamma"))  // pbrt-v3: "bool gamma", true for sRGB-encoded files
    return ColorEncoding{ps.get_bool("gamma", false) ? ColorEncoding::SRGB : ColorEncoding::Linear};
  if (!p) return default_texture_encoding(file);
  std::string e = ps.get_string("encoding", "");
  if (e == "sRGB") return ColorEncoding{ColorEncoding::SRGB};
  if (e == "linear") return ColorEncoding{ColorEncoding::Linear};
  if (e.rfind("gamma ", 0) == 0) {
    char* end = nullptr;
    float g = std::strtof(e.c_str() + 6, &end);
    if (end != e.c_str() + 6 && *end == '\0' && g > 0.f && std::isfinite(g)) return ColorEncoding{ColorEncoding::Gamma, g};
  }
  ps.fail(*p, "encoding \"" + printable(e) + "\" is unknown; expected \"sRGB\", \"linear\" or \"gamma <value>\"");
}

static void parse_image_lookup(const ParamSet& ps, TextureNode* n) {
  // pbrt-v3: "bool trilinear" instead of a filter name.
  const char* v3 = ps.has("trilinear") && !ps.has("filter") ? (ps.get_bool("trilinear", false) ? "trilinear" : "bilinear")
                                                             : "bilinear";
  std::string filter = ps.get_string("filter", v3);
  if (filter == "point") n->filter = ImageFilter::Point;
  else if (filter == "bilinear") n->filter = ImageFilter::Bilinear;
  else if (filter == "trilinear") n->filter = ImageFilter::Trilinear;
  else if (filter == "ewa" || filter == "EWA") n->filter = ImageFilter::EWA;
  else ps.fail(*ps.find("filter"), "filter \"" + printable(filter) + "\" is unknown; expected point, bilinear, trilinear or ewa");
  n->max_anisotropy = ps.get_float("maxanisotropy", 8.f);
  if (!(n->max_anisotropy >= 1.f && n->max_anisotropy <= 1024.f))
    ps.fail(*ps.find("maxanisotropy"), "maxanisotropy must be in [1, 1024]");
  std::string wrap = ps.get_string("wrap", "repeat");
  if (wrap == "repeat") n->wrap = WrapMode::Repeat;
  else if (wrap == "black") n->wrap = WrapMode::Black;
  else if (wrap == "clamp") n->wrap = WrapMode::Clamp;
  else if (wrap == "octahedralsphere") n->wrap = WrapMode::OctahedralSphere;
  else ps.fail(*ps.find("wrap"), "wrap mode \"" + printable(wrap) + "\" is unknown; expected repeat, black, clamp or octahedralsphere");
  n->scale = ps.get_float("scale", 1.f);
  n->invert = ps.get_bool("invert", false);
}

void SceneBuilder::texture(const std::string& name, const std::string& value_type, const std::string& cls,
                           const ParamSet& ps, const Mat4& ctm, const std::string& base_dir) {
  const bool is_float = value_type == "float";
  if (!is_float && value_type != "spectrum" && value_type != "color" && value_type != "rgb")
    ps.fail("texture value type \"" + printable(value_type) + "\" is unknown; expected \"spectrum\" or \"float\"");
  auto child = [&](const char* p, float def) {
    return is_float ? broadcast(float_texture(ps, p, def)) : rgb_texture(ps, p, RGB(def));
  };
  auto constant = [&](const char* p, float def) {
    return is_float ? RGB(ps.get_float(p, def)) : ps.get_rgb(p, ColorUsage::Reflectance).value_or(RGB(def));
  };
  TextureNode n;
  n.is_float = is_float;
  RGBTextureRef result;  // a float texture's value in every channel
  if (cls == "constant") {
    // A spectrum's value keeps its spectrum (given by samples, or a colour
    // of another space) as a material's constant parameter does.
    if (is_float || ps.get_texture("value")) result = RGBTextureRef::constant(constant("value", 1.f));
    else result = rgb_texture(ps, "value", RGB(1.f));
  } else if (cls == "imagemap") {
    std::string file = ps.get_string("filename", "");
    if (file.empty()) ps.fail("imagemap texture needs a \"filename\"");
    n.kind = TextureKind::Image;
    n.mapping = texture_mapping(ps, ctm, true);
    parse_image_lookup(ps, &n);
    const std::string path = resolve_path(base_dir, file);
    const ColorEncoding encoding = parse_encoding(ps, file);
    // OpenImageIO has no octahedral wrap: such images stay resident and
    // are read bilinearly (they are environment-sized, not scene-sized).
    // Small images read without MIP filtering stay resident too, within a
    // fixed budget: a lookup there costs a quarter of the cache's
    // (docs/performance.md), and the budget, not the cache size, bounds them.
    if (n.wrap == WrapMode::OctahedralSphere || resident_fits(ps, path, encoding, n.filter)) {
      n.image = texture_image(ps, path, encoding);
    } else {
      n.cached = cached_texture(ps, path, encoding, n);
      if (n.filter == ImageFilter::Trilinear || n.filter == ImageFilter::EWA) scene_.textures.uses_footprint = true;
    }
    result = add_texture_node(n);
  } else if (cls == "checkerboard") {
    n.kind = TextureKind::Checkerboard;
    n.dimension = ps.get_int("dimension", 2);
    if (n.dimension != 2 && n.dimension != 3) ps.fail(*ps.find("dimension"), "checkerboard dimension must be 2 or 3");
    n.mapping = texture_mapping(ps, ctm, n.dimension == 2);
    n.tex1 = child("tex1", 1.f);
    n.tex2 = child("tex2", 0.f);
    scene_.textures.uses_footprint = true;  // filtered over it
    result = add_texture_node(n);
  } else if (cls == "dots") {
    n.kind = TextureKind::Dots;
    n.mapping = texture_mapping(ps, ctm, true);
    // pbrt-v4 hands "inside" to the texture's outside-of-the-dots slot and
    // "outside" to the dots themselves; scenes are made to look right in it.
    n.tex1 = child("outside", 0.f);
    n.tex2 = child("inside", 1.f);
    result = add_texture_node(n);
  } else if (cls == "scale") {
    n.kind = TextureKind::Scale;
    if (ps.has("tex1") || ps.has("tex2")) {
      // pbrt-v3's product of tex1 and tex2: one of them becomes the float
      // scale (a number, a float texture or a grey colour), as pbrt-v4's
      // upgrade does.
      auto scalar = [&](const char* p) {
        const pbrt::Param* q = ps.find(p);
        if (!q || q->type == "float") return true;
        if (q->type == "texture") return is_float || float_textures_.count(ps.get_texture(p).value_or("")) > 0;
        std::optional<RGB> c = ps.get_rgb(p, ColorUsage::Unbounded);
        return c && (*c)[0] == (*c)[1] && (*c)[1] == (*c)[2];
      };
      const bool swap = !scalar("tex2") && scalar("tex1");
      if (!scalar(swap ? "tex1" : "tex2"))
        ps.fail("pbrt-v3 \"scale\" of two colour textures: one of \"tex1\" and \"tex2\" must be a float or a grey "
                "constant (as pbrt-v4's upgrade requires)");
      const char* tex = swap ? "tex2" : "tex1";
      const char* by = swap ? "tex1" : "tex2";
      n.tex1 = child(tex, 1.f);
      const pbrt::Param* q = ps.find(by);
      n.tex2 = q && q->type != "float" && q->type != "texture"
                   ? RGBTextureRef::constant(RGB((*ps.get_rgb(by, ColorUsage::Unbounded))[0]))
                   : broadcast(float_texture(ps, by, 1.f));
    } else {
      n.tex1 = child("tex", 1.f);
      n.tex2 = broadcast(float_texture(ps, "scale", 1.f));
    }
    // Two constants fold into one, unless the first holds a spectrum (the
    // node then scales it by wavelength).
    const bool fold = n.tex1.is_constant() && n.tex2.is_constant() && n.tex1.spectrum < 0;
    result = fold ? RGBTextureRef::constant(n.tex1.value * n.tex2.value[0]) : add_texture_node(n);
  } else if (cls == "mix" || cls == "directionmix") {
    n.kind = cls == "mix" ? TextureKind::Mix : TextureKind::DirectionMix;
    n.tex1 = child("tex1", 0.f);
    n.tex2 = child("tex2", 1.f);
    if (cls == "mix") {
      n.amount = float_texture(ps, "amount", 0.5f);
    } else {
      Vec3 d = glm::mat3(ctm) * ps.get_point3("dir", Vec3(0, 1, 0));
      if (!(glm::length(d) > 0.f) || !is_finite(d)) ps.fail(*ps.find("dir"), "dir must be a non-zero direction");
      n.dir = glm::normalize(d);
    }
    result = add_texture_node(n);
  } else if (cls == "bilerp") {
    n.kind = TextureKind::Bilerp;
    n.mapping = texture_mapping(ps, ctm, true);
    n.v00 = constant("v00", 0.f);
    n.v01 = constant("v01", 1.f);
    n.v10 = constant("v10", 0.f);
    n.v11 = constant("v11", 1.f);
    result = add_texture_node(n);
  } else if ((is_float && (cls == "fbm" || cls == "wrinkled" || cls == "windy")) || (!is_float && cls == "marble")) {
    n.kind = cls == "fbm" ? TextureKind::FBm : cls == "wrinkled" ? TextureKind::Wrinkled
                          : cls == "windy" ? TextureKind::Windy : TextureKind::Marble;
    n.mapping = texture_mapping(ps, ctm, false);
    if (n.kind != TextureKind::Windy) {
      n.octaves = ps.get_int("octaves", 8);
      if (n.octaves < 0 || n.octaves > 64) ps.fail(*ps.find("octaves"), "octaves must be in [0, 64]");
      n.roughness = ps.get_float("roughness", 0.5f);
    }
    if (n.kind == TextureKind::Marble) {
      n.scale = ps.get_float("scale", 1.f);
      n.variation = ps.get_float("variation", 0.2f);
    }
    scene_.textures.uses_footprint = true;  // octaves finer than it are left out
    result = add_texture_node(n);
  } else if (cls == "ptex") {
    ps.fail("ptex textures are not supported: Lantern reads images through OpenImageIO, whose Debian build has no Ptex");
  } else {
    ps.fail(std::string(is_float ? "float" : "spectrum") + " texture class \"" + printable(cls) +
            "\" is not supported; expected " +
            (is_float ? "constant, imagemap, checkerboard, dots, scale, mix, directionmix, bilerp, fbm, wrinkled or windy"
                      : "constant, imagemap, checkerboard, dots, scale, mix, directionmix, bilerp or marble"));
  }
  if ((is_float ? float_textures_.count(name) : rgb_textures_.count(name)) > 0)
    warn(ps.where, "texture \"" + printable(name) + "\" is redefined");
  if (is_float) float_textures_[name] = FloatTextureRef{result.value[0], result.node, -1};
  else rgb_textures_[name] = result;
}

}  // namespace lantern
