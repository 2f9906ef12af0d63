// Materials from pbrt-v4's parameter lists (and pbrt-v3's names of the
// common ones): every parameter pbrt-v4 lets be a texture may be one.
#include "scene/builder.h"

#include <algorithm>

#include "color/densely_sampled_spectrum.h"
#include "color/glass.h"
#include "color/optical_constants.h"

namespace lantern {

using pbrt::ColorUsage;
using pbrt::ParamSet;

RoughnessParams SceneBuilder::roughness(const ParamSet& ps, float def, const std::string& prefix) {
  RoughnessParams r;
  const std::string names[3] = {prefix + "roughness", prefix + "uroughness", prefix + "vroughness"};
  FloatTextureRef both = float_texture(ps, names[0], def);
  r.u = ps.has(names[1]) ? float_texture(ps, names[1], def) : both;
  r.v = ps.has(names[2]) ? float_texture(ps, names[2], def) : both;
  for (const std::string& name : names)
    if (const pbrt::Param* p = ps.find(name); p && p->type != "texture" && !(ps.get_float(name, 0.f) >= 0.f))
      ps.fail(*p, "roughness must be a number >= 0");
  r.remap = ps.get_bool("remaproughness", true);
  return r;
}

// The layer parameters of pbrt-v4's coated materials, with its defaults.
void SceneBuilder::coat_layer(const ParamSet& ps, CoatLayer* c) {
  c->albedo = rgb_texture(ps, "albedo", RGB(0.f));
  c->thickness = float_texture(ps, "thickness", 0.01f);
  if (c->thickness.is_constant() && !(c->thickness.value >= 0.f && std::isfinite(c->thickness.value)))
    ps.fail(*ps.find("thickness"), "thickness must be a finite number >= 0");
  c->g = float_texture(ps, "g", 0.f);
  if (c->g.is_constant() && !std::isfinite(c->g.value)) ps.fail(*ps.find("g"), "g must be finite");
  // Bounded so that no scene can make one evaluation take seconds.
  c->max_depth = ps.get_int("maxdepth", 10);
  if (c->max_depth < 0 || c->max_depth > 100) ps.fail(*ps.find("maxdepth"), "maxdepth must be in [0, 100]");
  c->n_samples = ps.get_int("nsamples", 1);
  if (c->n_samples < 1 || c->n_samples > 100) ps.fail(*ps.find("nsamples"), "nsamples must be in [1, 100]");
}

// A conductor's eta or k: as given, or pbrt-v4's default, copper's
// measured constants (named metal `def`), kept as a spectrum too.
RGBTextureRef SceneBuilder::conductor_param(const ParamSet& ps, const std::string& name, const std::string& def) {
  if (ps.has(name)) return rgb_texture(ps, name, RGB(0.f), ColorUsage::Unbounded);
  RGBTextureRef ref = RGBTextureRef::constant(*pbrt::named_spectrum_rgb(def));
  if (auto s = pbrt::named_sampled_spectrum(def)) ref.spectrum = add_spectrum(*s);
  return ref;
}

FloatTextureRef SceneBuilder::eta_param(const ParamSet& ps, float def, int32_t* dispersion) {
  const pbrt::Param* p = ps.find("eta");
  if (!p) p = ps.find("index");
  if (!p) return FloatTextureRef::constant(def);
  if (p->type == "texture") return float_texture(ps, p->name, def);
  // A sampled index (a named glass, a file or pairs): the RGB renderer
  // reads it at the helium d line, where glass catalogues quote n_d; the
  // spectral one reads it at the wavelengths (dispersion), where the
  // material keeps it.
  const auto sampled = ps.get_sampled_spectrum(p->name);
  float eta = sampled                ? float((*sampled)(kHeliumDLine))
              : p->type == "float" ? ps.get_float(p->name, def)
                                   : (*ps.get_rgb(p->name, ColorUsage::Unbounded))[0];
  if (!(eta > 0.f)) ps.fail(*p, "index of refraction must be positive");
  if (sampled && dispersion) *dispersion = dispersive_index(ps, *p, *sampled);
  return FloatTextureRef::constant(eta);
}

int32_t SceneBuilder::dispersive_index(const ParamSet& ps, const pbrt::Param& p, const PiecewiseLinearSpectrum& eta) {
  const DenselySampledSpectrum dense(eta);
  const auto [lo, hi] = std::minmax_element(dense.value.begin(), dense.value.end());
  if (!(*lo > 0.f)) ps.fail(p, "index of refraction must be positive at every wavelength from 360 to 830 nm");
  if (!(*hi > *lo)) return -1;
  scene_.settings.dispersive = true;
  return add_spectrum(eta);
}

int32_t SceneBuilder::bump_map(const ParamSet& ps, const std::string& base_dir) {
  BumpParams b;
  b.displacement = float_texture(ps, ps.has("bumpmap") ? "bumpmap" : "displacement", 0.f);  // pbrt-v3: "bumpmap"
  std::string file = ps.get_string("normalmap", "");
  if (!file.empty()) {
    // pbrt-v4 reads normal maps linearly, whatever the format, bilinearly
    // at full resolution and repeating.
    TextureNode lookup;
    lookup.filter = ImageFilter::Bilinear;
    lookup.wrap = WrapMode::Repeat;
    b.normal_map = cached_texture(ps, resolve_path(base_dir, file), ColorEncoding{ColorEncoding::Linear}, lookup,
                                  "normalmap");
    if (ps.has("displacement")) warn(ps.where, "both \"normalmap\" and \"displacement\" given: the normal map is used (as in pbrt-v4)");
  }
  if (b.normal_map < 0 && b.displacement.is_constant()) return -1;  // a constant displacement does not bend normals
  if (b.normal_map < 0) scene_.textures.uses_footprint = true;  // the displacement's finite differences span it
  scene_.materials.bumps.push_back(b);
  return int32_t(scene_.materials.bumps.size() - 1);
}

MaterialHandle SceneBuilder::material(const std::string& type, const ParamSet& ps,
                                      const std::map<std::string, MaterialHandle>& named, const std::string& base_dir) {
  if (type == "mix") return mix_material(ps, named);  // its materials keep their own bump maps
  MaterialHandle h = concrete_material(type, ps);
  if (h.kind() == MaterialKind::Interface) return h;
  if (int32_t b = bump_map(ps, base_dir); b >= 0) {
    if (int32_t* slot = scene_.materials.bump_index(h)) *slot = b;
    else if (h.kind() == MaterialKind::Hair) warn(ps.where, "hair takes no bump or normal map (nor does it in pbrt-v4); ignored");
  }
  return h;
}

MaterialHandle SceneBuilder::mix_material(const ParamSet& ps, const std::map<std::string, MaterialHandle>& named) {
  MaterialPools& m = scene_.materials;
  if (ps.has("namedmaterial1") || ps.has("namedmaterial2")) return mix_material_v3(ps, named);
  const pbrt::Param* p = ps.find("materials");
  if (!p || p->type != "string" || p->strings.size() != 2)
    ps.fail("mix needs \"string materials\" with the names of two materials defined with MakeNamedMaterial");
  MixMaterial mix;
  for (int i = 0; i < 2; ++i) {
    auto it = named.find(p->strings[size_t(i)]);
    if (it == named.end()) ps.fail(*p, "no material named \"" + printable(p->strings[size_t(i)]) + "\" was defined");
    if (it->second.kind() == MaterialKind::Interface) ps.fail(*p, "an \"interface\" material cannot be mixed");
    refuse_mixed_subsurface(ps, it->second);
    mix.materials[i] = it->second;
  }
  mix.amount = float_texture(ps, "amount", 0.5f);
  m.mix.push_back(mix);
  return MaterialHandle::make(MaterialKind::Mix, uint32_t(m.mix.size() - 1));
}

MaterialHandle SceneBuilder::concrete_material(const std::string& type, const ParamSet& ps) {
  MaterialPools& m = scene_.materials;
  if (type == "interface") return MaterialHandle::make(MaterialKind::Interface, 0);
  if (type == "diffuse" || type == "matte") {
    m.diffuse.push_back({rgb_texture(ps, ps.has("Kd") ? "Kd" : "reflectance", RGB(0.5f))});
    ps.find("sigma");
    return MaterialHandle::make(MaterialKind::Diffuse, uint32_t(m.diffuse.size() - 1));
  }
  if (type == "conductor" || type == "metal" || type == "mirror") {
    ConductorMaterial c;
    if (type == "mirror") {
      c.mirror = true;
      c.mirror_reflectance = rgb_texture(ps, "Kr", RGB(0.9f));
    } else {
      // Sampled eta and k (files, inline pairs, named metals) are fitted
      // together, as the named metals are: the RGB conductor whose Fresnel
      // curve matches theirs (color/optical_constants.h). Otherwise each is
      // read on its own (RGB, a texture, a named spectrum's fit).
      const auto eta_s = ps.get_sampled_spectrum("eta"), k_s = ps.get_sampled_spectrum("k");
      if (eta_s && k_s) {
        std::vector<OpticalConstant> table;
        for (int nm = 360; nm <= 830; ++nm)
          table.push_back({float(nm), float((*eta_s)(nm)), float((*k_s)(nm))});
        const ConductorRGB fit = fit_conductor_rgb(table);
        c.eta = RGBTextureRef::constant(fit.eta);
        c.k = RGBTextureRef::constant(fit.k);
        c.eta.spectrum = add_spectrum(*eta_s);
        c.k.spectrum = add_spectrum(*k_s);
      } else {
        c.eta = conductor_param(ps, "eta", "metal-Cu-eta");
        c.k = conductor_param(ps, "k", "metal-Cu-k");
      }
      if (ps.has("reflectance")) {
        c.reflectance = rgb_texture(ps, "reflectance", RGB(0.f));
        // pbrt-v4: a conductor given by its reflectance at normal
        // incidence, eta 1 and k from it per wavelength when shading
        // (bsdf_kernel.h). (k computed here from the RGB, as it once was
        // for a constant, is a k whose spectrum is not the reflectance's:
        // spectral renders came out 7% bright in red and blue.)
        c.by_reflectance = true;
      }
      c.roughness = roughness(ps, type == "metal" ? 0.01f : 0.f);
    }
    m.conductor.push_back(c);
    return MaterialHandle::make(MaterialKind::Conductor, uint32_t(m.conductor.size() - 1));
  }
  if (type == "dielectric" || type == "glass") {
    DielectricMaterial d;
    d.eta = eta_param(ps, 1.5f, &d.dispersion);
    d.roughness = roughness(ps, 0.f);
    for (const char* p : {"Kr", "Kt"}) ps.find(p);
    m.dielectric.push_back(d);
    return MaterialHandle::make(MaterialKind::Dielectric, uint32_t(m.dielectric.size() - 1));
  }
  if (type == "coateddiffuse" || type == "plastic") {
    CoatedDiffuseMaterial c;
    bool v3 = type == "plastic";
    c.reflectance = rgb_texture(ps, v3 ? "Kd" : "reflectance", RGB(v3 ? 0.25f : 0.5f));
    if (const pbrt::Param* ks = v3 ? ps.find("Ks") : nullptr; ks && ks->type != "texture") {
      // pbrt-v4's upgrade makes a plastic without a specular part diffuse.
      const std::optional<RGB> k = ks->type == "float" ? std::optional<RGB>(RGB(ps.get_float("Ks", 0.f)))
                                                       : ps.get_rgb("Ks", ColorUsage::Reflectance);
      if (k && *k == RGB(0.f)) {
        for (const char* p : {"eta", "index", "roughness", "uroughness", "vroughness", "remaproughness"}) ps.find(p);
        m.diffuse.push_back({c.reflectance});
        return MaterialHandle::make(MaterialKind::Diffuse, uint32_t(m.diffuse.size() - 1));
      }
    }
    FloatTextureRef eta = eta_param(ps, 1.5f, &c.dispersion);
    if (!eta.is_constant()) ps.fail(*ps.find("eta"), "coateddiffuse's eta is a spectrum in pbrt-v4, not a texture");
    c.eta = eta.value;
    c.roughness = roughness(ps, v3 ? 0.1f : 0.f);
    coat_layer(ps, &c.layer);
    m.coated_diffuse.push_back(c);
    return MaterialHandle::make(MaterialKind::CoatedDiffuse, uint32_t(m.coated_diffuse.size() - 1));
  }
  if (type == "coatedconductor") return coated_conductor(ps);
  if (type == "subsurface" || type == "kdsubsurface") return subsurface_material(type, ps);
  if (auto v3 = v3_material(type, ps)) return *v3;
  if (type == "diffusetransmission") {
    DiffuseTransmissionMaterial d;
    d.reflectance = rgb_texture(ps, "reflectance", RGB(0.25f));
    d.transmittance = rgb_texture(ps, "transmittance", RGB(0.25f));
    d.scale = ps.get_float("scale", 1.f);
    if (!(d.scale >= 0.f) || !std::isfinite(d.scale)) ps.fail(*ps.find("scale"), "\"scale\" must be a finite number >= 0");
    m.diffuse_transmission.push_back(d);
    return MaterialHandle::make(MaterialKind::DiffuseTransmission, uint32_t(m.diffuse_transmission.size() - 1));
  }
  if (type == "hair") return hair_material(ps);
  if (type == "measured") return measured_material(ps);
  if (type == "thindielectric") {
    ThinDielectricMaterial d;
    d.eta = eta_param(ps, 1.5f, &d.dispersion);
    m.thin_dielectric.push_back(d);
    return MaterialHandle::make(MaterialKind::ThinDielectric, uint32_t(m.thin_dielectric.size() - 1));
  }
  // pbrt-v3 renders a material type it does not know as matte, with a
  // warning; so does Lantern (scenes exported for other renderers name
  // their own types).
  warn(ps.where, ps.directive + ": material type \"" + printable(type) +
                     "\" is unknown and renders as \"diffuse\" (pbrt-v3's matte) from its \"Kd\" or \"reflectance\"; "
                     "known: diffuse, conductor, dielectric, thindielectric, diffusetransmission, coateddiffuse, "
                     "coatedconductor, hair, measured, subsurface, mix, interface (and pbrt-v3's matte, metal, glass, plastic, mirror, uber, "
                     "substrate, translucent, kdsubsurface, fourier)");
  return concrete_material("diffuse", ps);
}

// pbrt-v4's measured: "filename" names a tabulated BRDF (relative to the
// scene's file), read once however many materials name it.
MaterialHandle SceneBuilder::measured_material(const ParamSet& ps) {
  MaterialPools& m = scene_.materials;
  const MeasuredBRDF* brdf =
      tabulated_bsdf_file(ps, "filename", "the measured material needs a \"filename\" (a tabulated BSDF, .bsdf)",
                          measured_files_, m.measured_brdfs, MeasuredBRDF::load);
  m.measured.push_back({brdf, -1});
  return MaterialHandle::make(MaterialKind::Measured, uint32_t(m.measured.size() - 1));
}

// pbrt-v4's coatedconductor, with its parameter names and defaults.
MaterialHandle SceneBuilder::coated_conductor(const ParamSet& ps) {
  CoatedConductorMaterial c;
  c.interface_roughness = roughness(ps, 0.f, "interface.");
  c.conductor_roughness = roughness(ps, 0.f, "conductor.");
  if (const pbrt::Param* p = ps.find("interface.eta")) {
    float eta = p->type == "float" ? ps.get_float(p->name, 1.5f) : (*ps.get_rgb(p->name, ColorUsage::Unbounded))[0];
    if (!(eta >= 0.f) || !std::isfinite(eta)) ps.fail(*p, "index of refraction must be a finite number >= 0");
    c.interface_eta = eta == 0.f ? 1.f : eta;  // pbrt-v4 reads 0 as 1
    if (const auto sampled = ps.get_sampled_spectrum(p->name)) {
      c.interface_eta = float((*sampled)(kHeliumDLine));
      c.dispersion = dispersive_index(ps, *p, *sampled);
    }
  }
  if (ps.has("reflectance")) {
    if (ps.has("conductor.eta") || ps.has("conductor.k"))
      ps.fail(*ps.find("reflectance"), "give either \"reflectance\" or \"conductor.eta\" and \"conductor.k\", not both");
    c.reflectance = rgb_texture(ps, "reflectance", RGB(0.f));
    c.by_reflectance = true;
  } else {
    c.conductor_eta = conductor_param(ps, "conductor.eta", "metal-Cu-eta");
    c.conductor_k = conductor_param(ps, "conductor.k", "metal-Cu-k");
  }
  coat_layer(ps, &c.layer);
  MaterialPools& m = scene_.materials;
  m.coated_conductor.push_back(c);
  return MaterialHandle::make(MaterialKind::CoatedConductor, uint32_t(m.coated_conductor.size() - 1));
}

// pbrt-v4's hair: sigma_a, or reflectance (pbrt-v3: color), or eumelanin
// and pheomelanin; with none of them, eumelanin 1.3.
MaterialHandle SceneBuilder::hair_material(const ParamSet& ps) {
  HairMaterial h;
  const char* refl = ps.has("reflectance") ? "reflectance" : "color";
  const bool melanin = ps.has("eumelanin") || ps.has("pheomelanin");
  if (ps.has("sigma_a")) {
    if (ps.has(refl)) ps.fail(*ps.find(refl), "give hair either \"sigma_a\" or \"" + std::string(refl) + "\", not both");
    if (melanin) warn(ps.where, "hair's \"sigma_a\" is given: its melanin concentrations are ignored (as in pbrt-v4)");
    h.by = HairMaterial::Absorption::SigmaA;
    h.sigma_a = rgb_texture(ps, "sigma_a", RGB(0.f), ColorUsage::Unbounded);
  } else if (ps.has(refl)) {
    if (melanin) warn(ps.where, "hair's \"" + std::string(refl) + "\" is given: its melanin concentrations are ignored (as in pbrt-v4)");
    h.by = HairMaterial::Absorption::Reflectance;
    h.reflectance = rgb_texture(ps, refl, RGB(0.f));
  } else if (melanin) {
    h.eumelanin = float_texture(ps, "eumelanin", 0.f);
    h.pheomelanin = float_texture(ps, "pheomelanin", 0.f);
  }
  for (const char* p : {"eumelanin", "pheomelanin"}) ps.find(p);  // read, even when ignored
  h.eta = float_texture(ps, "eta", 1.55f);
  h.beta_m = float_texture(ps, "beta_m", 0.3f);
  h.beta_n = float_texture(ps, "beta_n", 0.3f);
  h.alpha = float_texture(ps, "alpha", 2.f);
  MaterialPools& m = scene_.materials;
  m.hair.push_back(h);
  return MaterialHandle::make(MaterialKind::Hair, uint32_t(m.hair.size() - 1));
}

MaterialHandle SceneBuilder::default_material() {
  if (!default_material_) {
    scene_.materials.diffuse.push_back({RGBTextureRef::constant(RGB(0.5f))});
    default_material_ = MaterialHandle::make(MaterialKind::Diffuse, uint32_t(scene_.materials.diffuse.size() - 1));
  }
  return *default_material_;
}

}  // namespace lantern
