// pbrt's "subsurface" (pbrt-v4, pbrt-v3) and pbrt-v3's "kdsubsurface" as
// what they describe: a dielectric boundary with a homogeneous scattering
// medium inside the shape. pbrt-v4 approximates that interior by a
// tabulated BSSRDF (photon beam diffusion) and probe rays, which
// bidirectional estimators cannot connect to; the medium is traced by
// every integrator as any other (a random walk: path, bdpt, lt, vcm), and
// is the exact transport the BSSRDF approximates (docs/materials.md).
#include "material/subsurface_albedo.h"
#include "medium/presets.h"
#include "scene/builder.h"

namespace lantern {

using pbrt::ColorUsage;
using pbrt::ParamSet;

namespace {

// A constant colour parameter: the interior is one homogeneous medium, so
// a texture cannot vary it.
std::optional<RGB> constant_rgb(const ParamSet& ps, const char* name, ColorUsage usage) {
  const pbrt::Param* p = ps.find(name);
  if (!p) return std::nullopt;
  if (p->type == "texture")
    ps.fail(*p, "a textured subsurface coefficient is not supported: the interior is one homogeneous medium");
  if (p->type == "float") return RGB(ps.get_float(name, 0.f));
  return ps.get_rgb(name, usage);
}

RGB checked(const ParamSet& ps, const char* name, const RGB& v) {
  if (!is_finite(v) || v[0] < 0.f || v[1] < 0.f || v[2] < 0.f) {
    const std::string what = std::string("\"") + name + "\" (times \"scale\") must be finite and not negative";
    if (const pbrt::Param* p = ps.find(name)) ps.fail(*p, what);
    ps.fail(what);
  }
  return v;
}

}  // namespace

// The interior's coefficients from pbrt-v4's four mutually exclusive
// forms, in its order: a named measured medium, sigma_a and sigma_s, a
// reflectance (pbrt-v3's kdsubsurface: Kd) with a mean free path, or the
// defaults (per mm); "scale" multiplies the coefficients and the mean free
// path alike, as in pbrt-v4. A reflectance is what a thick slab of the
// medium under this boundary gives back of the light entering it
// (material/subsurface_albedo.h); pbrt-v4 inverts its diffusion model's
// for the same purpose.
HomogeneousMedium SceneBuilder::subsurface_interior(const ParamSet& ps, const std::string& type, float eta) {
  HomogeneousMedium m;
  m.g = ps.get_float("g", 0.f);
  if (!(m.g > -1.f && m.g < 1.f)) ps.fail(*ps.find("g"), "\"g\" must lie strictly between -1 and 1");
  const float scale = ps.get_float("scale", 1.f);
  if (!(scale > 0.f) || !std::isfinite(scale)) ps.fail(*ps.find("scale"), "\"scale\" must be a finite number > 0");
  const std::string name = type == "kdsubsurface" ? "" : ps.get_string("name", "");
  if (!name.empty()) {
    const auto preset = medium_preset(name);
    if (!preset) ps.fail(*ps.find("name"), "unknown measured medium \"" + printable(name) + "\"; known: " + medium_preset_names());
    if (m.g != 0.f && ps.warn && *ps.warn)
      (*ps.warn)(ps.find("g")->where.str() + ": warning: " + ps.directive +
                 ": \"g\" is ignored with a named medium, whose coefficients are reduced ones (as in pbrt-v4)");
    m.g = 0.f;
    m.sigma_a = preset->sigma_a * scale;
    m.sigma_s = preset->sigma_s * scale;
    return m;
  }
  const std::optional<RGB> sigma_a = constant_rgb(ps, "sigma_a", ColorUsage::Unbounded);
  const std::optional<RGB> sigma_s = constant_rgb(ps, "sigma_s", ColorUsage::Unbounded);
  if (sigma_a.has_value() != sigma_s.has_value())
    ps.fail(*ps.find(sigma_a ? "sigma_a" : "sigma_s"), "give \"sigma_a\" and \"sigma_s\" together");
  if (sigma_a) {
    m.sigma_a = checked(ps, "sigma_a", *sigma_a * scale);
    m.sigma_s = checked(ps, "sigma_s", *sigma_s * scale);
    return m;
  }
  const char* reflectance_name = type == "kdsubsurface" ? "Kd" : "reflectance";
  std::optional<RGB> reflectance = constant_rgb(ps, reflectance_name, ColorUsage::Reflectance);
  if (!reflectance && type == "kdsubsurface") reflectance = RGB(0.5f);
  if (reflectance) {
    const std::optional<RGB> mfp = constant_rgb(ps, "mfp", ColorUsage::Unbounded);
    const RGB free_path = checked(ps, "mfp", mfp.value_or(RGB(1.f)) * scale);
    auto table = slab_tables_.find({eta, m.g});
    if (table == slab_tables_.end()) table = slab_tables_.emplace(std::pair(eta, m.g), SlabAlbedoTable(eta, m.g)).first;
    for (int c = 0; c < 3; ++c) {
      if (!(free_path[c] > 0.f)) ps.fail(*ps.find("mfp"), "\"mfp\" must be > 0");
      const float albedo = table->second.single_scattering_albedo((*reflectance)[c]);
      m.sigma_s[c] = albedo / free_path[c];
      m.sigma_a[c] = (1.f - albedo) / free_path[c];
    }
    return m;
  }
  m.sigma_a = RGB(0.0011f, 0.0024f, 0.014f) * scale;
  m.sigma_s = RGB(2.55f, 3.21f, 3.77f) * scale;
  return m;
}

MaterialHandle SceneBuilder::subsurface_material(const std::string& type, const ParamSet& ps) {
  MaterialPools& m = scene_.materials;
  DielectricMaterial boundary;
  const pbrt::Param* eta = ps.find("eta");
  const float eta_value = eta && eta->type != "float" ? eta_param(ps, 1.33f).value : ps.get_float("eta", 1.33f);
  if (!(eta_value > 0.f) || !std::isfinite(eta_value)) ps.fail(*ps.find("eta"), "\"eta\" must be a finite number > 0");
  boundary.eta = FloatTextureRef::constant(eta_value);
  boundary.roughness = roughness(ps, 0.f);
  // pbrt-v3's reflection and transmission scales: 1 is the physics.
  for (const char* p : {"Kr", "Kt"})
    if (const std::optional<RGB> k = constant_rgb(ps, p, ColorUsage::Reflectance); k && *k != RGB(1.f))
      ps.fail(*ps.find(p), std::string("\"") + p + "\" other than 1 is not supported (nor by pbrt-v4)");
  const HomogeneousMedium inside = subsurface_interior(ps, type, eta_value);
  m.dielectric.push_back(boundary);
  const MaterialHandle h = MaterialHandle::make(MaterialKind::Dielectric, uint32_t(m.dielectric.size() - 1));
  scene_.media.homogeneous.push_back(inside);
  subsurface_media_[h.bits] = MediumHandle::make(MediumKind::Homogeneous, uint32_t(scene_.media.homogeneous.size() - 1));
  return h;
}

// A shape of a subsurface material holds its interior: the medium inside
// each of geometries [first, end), whatever MediumInterface says inside.
void SceneBuilder::assign_subsurface_media(size_t first, const GraphicsState& gs, const ParamSet& ps) {
  if (!gs.material) return;
  const auto it = subsurface_media_.find(gs.material->bits);
  if (it == subsurface_media_.end()) return;
  ShapePools& s = scene_.shapes;
  for (size_t g = first; g < s.geometries.size(); ++g) {
    if (s.geometries[g].kind == ShapeKind::Curve)
      ps.fail("a curve cannot have a subsurface material: it encloses no volume for the medium");
    s.geometries[g].media.inside = it->second;
  }
}

// A mix picks one material per hit; a medium belongs to the whole shape.
void SceneBuilder::refuse_mixed_subsurface(const ParamSet& ps, MaterialHandle h) const {
  if (subsurface_media_.count(h.bits))
    ps.fail("a subsurface material cannot be mixed: its interior medium fills the whole shape");
}

}  // namespace lantern
