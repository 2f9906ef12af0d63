// pbrt-v3's materials, read as pbrt-v4's own upgrade (pbrt --upgrade)
// rewrites them, and the materials Lantern refuses with a reason.
#include "scene/builder.h"

namespace lantern {

using pbrt::ColorUsage;
using pbrt::ParamSet;

namespace {

// Reads a pbrt-v3 parameter that has no pbrt-v4 equivalent; true when it
// was given as the constant `value` (the case the upgrade drops silently),
// otherwise a warning says it was dropped.
bool dropped_if_constant(const ParamSet& ps, const char* name, float value, const std::string& as) {
  const pbrt::Param* p = ps.find(name);
  if (!p) return false;
  if (p->type != "texture") {
    std::optional<RGB> c = p->type == "float" ? std::optional<RGB>(RGB(ps.get_float(name, value)))
                                              : ps.get_rgb(name, ColorUsage::Unbounded);
    if (c && *c == RGB(value)) return true;
  } else {
    ps.get_texture(name);
  }
  if (ps.warn)
    (*ps.warn)(p->where.str() + ": warning: " + ps.directive + ": parameter \"" + name + "\" dropped: " + as +
               " has no equivalent (as pbrt-v4 upgrades pbrt-v3 files)");
  return false;
}

}  // namespace

std::optional<MaterialHandle> SceneBuilder::v3_material(const std::string& type, const ParamSet& ps) {
  MaterialPools& m = scene_.materials;
  if (type == "uber" || type == "substrate") {
    if (type == "uber") {
      dropped_if_constant(ps, "Kr", 0.f, "coateddiffuse");
      dropped_if_constant(ps, "Kt", 0.f, "coateddiffuse");
      if (const pbrt::Param* o = ps.find("opacity")) {
        std::optional<RGB> c = o->type == "texture" ? std::nullopt : ps.get_rgb("opacity", ColorUsage::Reflectance);
        if (!c || *c != RGB(1.f))
          ps.fail(*o, "a non-opaque \"opacity\" in \"uber\" is not supported (nor by pbrt-v4); cut the shape "
                      "out with \"alpha\" instead");
      }
      if (dropped_if_constant(ps, "Ks", 0.f, "coateddiffuse")) {  // Ks = 0: plain diffuse
        for (const char* p : {"eta", "index", "roughness", "uroughness", "vroughness", "remaproughness"}) ps.find(p);
        m.diffuse.push_back({rgb_texture(ps, "Kd", RGB(0.5f))});
        return MaterialHandle::make(MaterialKind::Diffuse, uint32_t(m.diffuse.size() - 1));
      }
    } else {
      dropped_if_constant(ps, "Ks", 1.f, "coateddiffuse");
    }
    CoatedDiffuseMaterial c;
    c.reflectance = rgb_texture(ps, "Kd", RGB(0.5f));
    FloatTextureRef eta = eta_param(ps, 1.5f);
    if (!eta.is_constant()) ps.fail("coateddiffuse's eta is a spectrum in pbrt-v4, not a texture");
    c.eta = eta.value;
    c.roughness = roughness(ps, 0.f);
    coat_layer(ps, &c.layer);
    m.coated_diffuse.push_back(c);
    return MaterialHandle::make(MaterialKind::CoatedDiffuse, uint32_t(m.coated_diffuse.size() - 1));
  }
  if (type == "translucent") {
    dropped_if_constant(ps, "reflect", 0.f, "diffusetransmission");
    dropped_if_constant(ps, "transmit", 1.f, "diffusetransmission");
    dropped_if_constant(ps, "Ks", 0.f, "diffusetransmission");
    for (const char* p : {"roughness", "remaproughness"}) ps.find(p);
    DiffuseTransmissionMaterial d;
    d.transmittance = rgb_texture(ps, "Kd", RGB(0.25f));
    d.reflectance = rgb_texture(ps, "reflectance", RGB(0.25f));
    m.diffuse_transmission.push_back(d);
    return MaterialHandle::make(MaterialKind::DiffuseTransmission, uint32_t(m.diffuse_transmission.size() - 1));
  }
  if (type == "fourier") return fourier_material(ps);
  if (type == "disney") {
    // pbrt-v4 has no Disney BSDF: its upgrade writes a diffuse material of
    // the base "color"; the lobes beyond it are dropped, and said so.
    static const char* const kLobes[] = {"anisotropic", "clearcoat", "clearcoatgloss", "difftrans", "eta",
                                         "flatness", "metallic", "roughness", "scatterdistance", "sheen",
                                         "sheentint", "spectrans", "speculartint", "thin"};
    for (const char* p : kLobes) ps.find(p);
    warn(ps.where, "the disney material is not in pbrt-v4: rendering its \"color\" as a diffuse reflectance, as "
                   "pbrt-v4's upgrade names it; its other lobes are dropped");
    m.diffuse.push_back({rgb_texture(ps, "color", RGB(0.5f))});
    return MaterialHandle::make(MaterialKind::Diffuse, uint32_t(m.diffuse.size() - 1));
  }
  return std::nullopt;
}

// pbrt-v3's fourier: "bsdffile" names a Fourier BSDF table (relative to
// the scene's file), read once however many materials name it.
MaterialHandle SceneBuilder::fourier_material(const ParamSet& ps) {
  MaterialPools& m = scene_.materials;
  const FourierTable* table =
      tabulated_bsdf_file(ps, "bsdffile", "the fourier material needs a \"bsdffile\" (a Fourier BSDF table, .bsdf)",
                          fourier_files_, m.fourier_tables, FourierTable::load);
  m.fourier.push_back({table, -1});
  return MaterialHandle::make(MaterialKind::Fourier, uint32_t(m.fourier.size() - 1));
}

// pbrt-v3's mix: "namedmaterial1" with weight "amount" (a colour there; its
// average when it is not grey), "namedmaterial2" with the rest. pbrt-v4's
// mix picks materials[1] with probability amount, so the order swaps.
MaterialHandle SceneBuilder::mix_material_v3(const ParamSet& ps, const std::map<std::string, MaterialHandle>& named) {
  MixMaterial mix;
  const char* names[2] = {"namedmaterial2", "namedmaterial1"};
  for (int i = 0; i < 2; ++i) {
    const pbrt::Param* p = ps.find(names[i]);
    if (!p) ps.fail(std::string("a pbrt-v3 mix needs both \"namedmaterial1\" and \"namedmaterial2\""));
    std::string n = ps.get_string(names[i], "");
    auto it = named.find(n);
    if (it == named.end()) ps.fail(*p, "no material named \"" + printable(n) + "\" was defined");
    if (it->second.kind() == MaterialKind::Interface) ps.fail(*p, "an \"interface\" material cannot be mixed");
    refuse_mixed_subsurface(ps, it->second);
    mix.materials[i] = it->second;
  }
  const pbrt::Param* a = ps.find("amount");
  if (a && a->type != "float" && a->type != "texture") {
    RGB c = ps.get_rgb("amount", ColorUsage::Reflectance).value_or(RGB(0.5f));
    float avg = (c[0] + c[1] + c[2]) / 3.f;
    if (c[0] != c[1] || c[1] != c[2])
      warn(a->where, "mix \"amount\" (" + std::to_string(c[0]) + ", " + std::to_string(c[1]) + ", " + std::to_string(c[2]) +
                         ") is coloured: its average " + std::to_string(avg) + " is used (as pbrt-v4's upgrade does)");
    mix.amount = FloatTextureRef::constant(avg);
  } else {
    mix.amount = float_texture(ps, "amount", 0.5f);
  }
  scene_.materials.mix.push_back(mix);
  return MaterialHandle::make(MaterialKind::Mix, uint32_t(scene_.materials.mix.size() - 1));
}

}  // namespace lantern
