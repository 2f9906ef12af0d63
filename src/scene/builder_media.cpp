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
  if (!is_finite(v) || v[0] < 0.f || v[1] < 0.f || v[2] < 0.f) {
    std::string what = std::string("\"") + name + "\" times \"scale\" must be finite and not negative";
    if (const pbrt::Param* p = ps.find(name)) ps.fail(*p, what);
    ps.fail(what);
  }
  return v;
}

// A grid parameter's values must number nx * ny * nz (times `per` numbers
// each), counted in 64 bits before anything is allocated for the grid.
void expect_grid_count(const ParamSet& ps, const pbrt::Param& p, const GridLayout& g, uint64_t per) {
  const uint64_t count = uint64_t(g.nx) * uint64_t(g.ny) * uint64_t(g.nz);
  if (p.numbers.size() % per != 0 || p.numbers.size() / per != count)
    ps.fail(p, "has " + std::to_string(p.numbers.size() / per) + " values; expected nx * ny * nz = " +
                   std::to_string(count));
  for (double v : p.numbers)
    if (!(v >= 0.0) || !std::isfinite(v)) ps.fail(p, "grid values must be finite and not negative");
}


}  // namespace

void SceneBuilder::medium(const std::string& name, const ParamSet& ps, const Mat4& render_from_medium,
                          const std::string& base_dir) {
  if (named_media_.count(name)) ps.fail("medium \"" + printable(name) + "\" is defined twice");
  std::string type = ps.get_string("type", "");
  // pbrt-v3's grid of densities, pbrt-v4's uniformgrid (the same
  // parameters, and the same trilinear lookup between cell centres; what
  // pbrt-v4's upgrade intends, though its code tests the medium's name).
  if (type == "heterogeneous") type = "uniformgrid";
  const char* known = "homogeneous, uniformgrid, rgbgrid, cloud, nanovdb or pbrt-v3's heterogeneous";
  if (type.empty()) ps.fail(std::string("needs a \"string type\" parameter (") + known + ")");
  if (type != "homogeneous" && type != "uniformgrid" && type != "rgbgrid" && type != "cloud" && type != "nanovdb")
    ps.fail("unknown medium type \"" + printable(type) + "\"; expected " + known);
  const bool may_emit = type == "homogeneous" || type == "uniformgrid" || type == "rgbgrid";
  if (const pbrt::Param* Le = ps.find("Le"); Le && !may_emit) {
    bool emits = false;
    for (double v : Le->numbers) emits |= v != 0.0;
    if (emits || !Le->strings.empty()) ps.fail(*Le, "\"Le\" is not a parameter of a " + type + " medium (pbrt-v4 ignores it)");
  }
  MediumPools& media = scene_.media;
  auto add = [&](MediumKind kind, size_t count) {
    const MediumHandle h = MediumHandle::make(kind, uint32_t(count - 1));
    named_media_[name] = h;
    if (media.emissive(h)) media.emissive_media.push_back(h);
  };
  if (type == "homogeneous") {
    HomogeneousMedium m = medium_coefficients(ps, true);
    m.Le = medium_Le(ps);
    if (max_component(m.Le) > 0.f)
      if (std::optional<PiecewiseLinearSpectrum> s = emission_spectrum(ps, "Le")) {
        m.Le_spectrum = int32_t(media.spectra.size());
        media.spectra.emplace_back(*s);
      }
    media.homogeneous.push_back(m);
    add(MediumKind::Homogeneous, media.homogeneous.size());
    return;
  }
  if (type == "nanovdb") {
    ps.find("Lescale");
    media.vdb.push_back(vdb_medium(ps, render_from_medium, base_dir));
    add(MediumKind::Vdb, media.vdb.size());
    return;
  }
  if (type == "cloud") {
    ps.find("Lescale");
    media.cloud.push_back(cloud(ps, render_from_medium));
    add(MediumKind::Cloud, media.cloud.size());
    return;
  }
  if (type == "rgbgrid") {
    media.rgb_grid.push_back(rgb_grid(ps, render_from_medium));
    add(MediumKind::RgbGrid, media.rgb_grid.size());
    return;
  }
  GridMedium g;
  g.per_density = medium_coefficients(ps, false);
  g.density = density_grid(ps, render_from_medium);
  g.emission = grid_emission(ps, g.density);
  media.grid.push_back(std::move(g));
  add(MediumKind::Grid, media.grid.size());
}

// A homogeneous medium's "Le" times "Lescale". As pbrt-v4 does for lights,
// a spectrum is normalised to luminance 1 (pbrt::ParamSet::get_rgb), an
// RGB value is taken as given.
RGB SceneBuilder::medium_Le(const ParamSet& ps) {
  const RGB Le = ps.get_rgb("Le", ColorUsage::Illuminant).value_or(RGB(0.f));
  const float scale = ps.get_float("Lescale", 1.f);
  if (!(max_component(Le) > 0.f)) return RGB(0.f);
  return checked_coefficient(ps, "Le", Le, scale);
}

// A uniformgrid's emission: "Le" (a spectrum) or "temperature" (one value
// per sample, a black body at (value - temperatureoffset) *
// temperaturescale kelvin, emitting above 100 K), times "Lescale" (one
// value per sample; 1 throughout when not given), as pbrt-v4 reads them.
GridEmission SceneBuilder::grid_emission(const ParamSet& ps, const DensityGrid& density) {
  GridEmission e;
  const pbrt::Param* Le = ps.find("Le");
  const pbrt::Param* temperature = ps.find("temperature");
  if (Le && temperature) ps.fail(*Le, "a uniformgrid takes \"Le\" or \"temperature\", not both");
  static_cast<GridLayout&>(e.scale) = density;
  static_cast<GridLayout&>(e.temperature) = density;
  if (const pbrt::Param* scale = ps.find("Lescale")) {
    expect_grid_count(ps, *scale, density, 1);
    e.scale.values = ps.get_floats("Lescale");
  } else {
    e.scale.nx = e.scale.ny = e.scale.nz = 1;  // one sample: it falls off towards the faces, as in pbrt-v4
    e.scale.values = {1.f};
  }
  if (Le) {
    e.Le = checked_coefficient(ps, "Le", ps.get_rgb("Le", ColorUsage::Illuminant).value_or(RGB(0.f)), 1.f);
    if (max_component(e.Le) > 0.f)
      if (std::optional<PiecewiseLinearSpectrum> s = emission_spectrum(ps, "Le")) e.Le_spectrum.emplace(*s);
  }
  const float offset = ps.get_float("temperatureoffset", ps.get_float("temperaturecutoff", 0.f));
  const float tscale = ps.get_float("temperaturescale", 1.f);
  if (!std::isfinite(offset) || !std::isfinite(tscale))
    ps.fail("\"temperatureoffset\" and \"temperaturescale\" must be finite");
  if (temperature) {
    const pbrt::Param& t = *temperature;
    if (t.numbers.size() != density.values.size())
      ps.fail(t, "has " + std::to_string(t.numbers.size()) + " values; expected as many as \"density\" (" +
                     std::to_string(density.values.size()) + ")");
    for (double v : t.numbers)
      if (!std::isfinite(float(v))) ps.fail(t, "temperatures must be finite");
    e.temperature.values = ps.get_floats("temperature");
    e.heat.offset = offset, e.heat.scale = tscale;
    float largest = 0.f;
    for (float v : e.temperature.values) largest = std::max(largest, std::fabs(v));
    if (!e.heat.tabulate(largest)) e.temperature.values.clear();  // nothing emits
  }
  return e;
}

// sigma_a, sigma_s (or a preset), scale and g, with pbrt-v4's defaults.
HomogeneousMedium SceneBuilder::medium_coefficients(const ParamSet& ps, bool presets) {
  RGB sigma_a(1.f), sigma_s(1.f);
  const std::string preset = presets ? ps.get_string("preset", "") : "";
  if (!preset.empty()) {
    auto p = medium_preset(preset);
    if (!p) ps.fail(*ps.find("preset"), "unknown preset \"" + printable(preset) + "\"; known: " + medium_preset_names());
    sigma_a = p->sigma_a;
    sigma_s = p->sigma_s;
    for (const char* name : {"sigma_a", "sigma_s"}) ps.find(name);  // as in pbrt-v4, a preset wins
  } else {
    sigma_a = ps.get_rgb("sigma_a", ColorUsage::Unbounded).value_or(sigma_a);
    sigma_s = ps.get_rgb("sigma_s", ColorUsage::Unbounded).value_or(sigma_s);
  }
  const float scale = ps.get_float("scale", 1.f);
  HomogeneousMedium m;
  m.sigma_a = checked_coefficient(ps, "sigma_a", sigma_a, scale);
  m.sigma_s = checked_coefficient(ps, "sigma_s", sigma_s, scale);
  if (preset.empty()) m.spectra = coefficient_spectra(ps, sigma_a, sigma_s, scale);
  m.g = ps.get_float("g", 0.f);
  if (!(m.g > -1.f && m.g < 1.f)) ps.fail(*ps.find("g"), "\"g\" must lie strictly between -1 and 1");
  return m;
}

// With sampled wavelengths pbrt-v4 reads a coefficient of another colour
// space by that space's table: so does Lantern (medium/coefficient_spectra.h),
// the other coefficient by sRGB's. Both times "scale". sigma_a and sigma_s
// are the sRGB values before the scale.
CoefficientSpectra SceneBuilder::coefficient_spectra(const ParamSet& ps, RGB sigma_a, RGB sigma_s, float scale) {
  CoefficientSpectra c;
  const pbrt::Param* a = ps.find("sigma_a");
  const pbrt::Param* s = ps.find("sigma_s");
  std::optional<UnboundedSpectrum> own_a = a ? color_space_shape(ps, *a, ColorUsage::Unbounded) : std::nullopt;
  std::optional<UnboundedSpectrum> own_s = s ? color_space_shape(ps, *s, ColorUsage::Unbounded) : std::nullopt;
  if (!own_a && !own_s) return c;
  c.given = true;
  c.sigma_a = own_a ? *own_a : unbounded_spectrum_of(sigma_a);
  c.sigma_s = own_s ? *own_s : unbounded_spectrum_of(sigma_s);
  c.sigma_a.scale *= scale;
  c.sigma_s.scale *= scale;
  return c;
}

// pbrt-v4's uniformgrid: "density" (nx * ny * nz values, x fastest) over
// the box p0..p1 of the medium's space.
// nx, ny, nz, p0, p1 and the medium's transform of a grid medium.
void SceneBuilder::grid_layout(const ParamSet& ps, const Mat4& render_from_medium, GridLayout* g) {
  g->nx = ps.get_int("nx", 1);
  g->ny = ps.get_int("ny", 1);
  g->nz = ps.get_int("nz", 1);
  if (g->nx < 1 || g->ny < 1 || g->nz < 1) ps.fail("\"nx\", \"ny\" and \"nz\" must be at least 1");
  g->p0 = ps.get_point3("p0", Vec3(0.f));
  g->p1 = ps.get_point3("p1", Vec3(1.f));
  if (!(g->p0.x < g->p1.x && g->p0.y < g->p1.y && g->p0.z < g->p1.z))
    ps.fail("\"p0\" must lie below \"p1\" on every axis");
  const float det = glm::determinant(render_from_medium);
  if (!std::isfinite(det) || det == 0.f) ps.fail("the medium's transform is singular");
  g->medium_from_render = glm::inverse(render_from_medium);
}


DensityGrid SceneBuilder::density_grid(const ParamSet& ps, const Mat4& render_from_medium) {
  DensityGrid g;
  grid_layout(ps, render_from_medium, &g);
  const pbrt::Param* density = ps.find("density");
  if (!density) ps.fail("a uniformgrid needs \"float density\" values");
  expect_grid_count(ps, *density, g, 1);
  g.values = ps.get_floats("density");
  g.find_occupied_cells();
  return g;
}

// pbrt-v4's rgbgrid: "rgb sigma_a" and/or "rgb sigma_s", one RGB value per
// sample, times "scale"; one not given is 1 (times scale) in the box. The
// values are in the colour space in effect: those of another than sRGB
// are kept as given for sampled wavelengths (medium/grid_density.h) and
// converted into sRGB (clamped into its gamut, one warning) for RGB.
RgbGridMedium SceneBuilder::rgb_grid(const ParamSet& ps, const Mat4& render_from_medium) {
  RgbGridMedium m;
  grid_layout(ps, render_from_medium, &m.grid);
  const float scale = ps.get_float("scale", 1.f);
  if (!(scale >= 0.f) || !std::isfinite(scale)) ps.fail(*ps.find("scale"), "\"scale\" must be finite and not negative");
  const pbrt::Param* a = ps.find("sigma_a");
  const pbrt::Param* s = ps.find("sigma_s");
  if (!a && !s) ps.fail("an rgbgrid needs \"rgb sigma_a\" and/or \"rgb sigma_s\" values");
  const bool other_space = ps.color_space && ps.color_space != &ColorSpace::srgb();
  if (other_space) m.grid.space = ps.color_space;
  auto read = [&](const pbrt::Param* p, std::vector<RGB>* out, std::vector<RGB>* own, RGB* constant, float scale,
                  ColorUsage usage) {
    if (!p) {
      *constant = RGB(scale);
      return;
    }
    if (p->type != "rgb" && p->type != "color") ps.fail(*p, "has type \"" + p->type + "\"; expected \"rgb\" values");
    expect_grid_count(ps, *p, m.grid, 3);
    bool warned = false;
    for (size_t i = 0; i < p->numbers.size(); i += 3) {
      const RGB given = RGB(float(p->numbers[i]), float(p->numbers[i + 1]), float(p->numbers[i + 2])) * scale;
      if (!is_finite(given)) ps.fail(*p, "values times \"scale\" must be finite");
      if (!other_space) {
        out->push_back(given);
        continue;
      }
      bool outside = false;
      out->push_back(ps.to_srgb(*p, given, usage, !warned, &outside));
      own->push_back(given);
      warned = warned || outside;
    }
  };
  read(a, &m.grid.sigma_a, &m.grid.own_a, &m.grid.constant_a, scale, ColorUsage::Unbounded);
  read(s, &m.grid.sigma_s, &m.grid.own_s, &m.grid.constant_s, scale, ColorUsage::Unbounded);
  if (const pbrt::Param* Le = ps.find("Le")) {  // emission, as pbrt-v4: only with sigma_a
    if (!a) ps.fail(*Le, "an rgbgrid with \"Le\" needs \"rgb sigma_a\" values");
    RGB unused;
    read(Le, &m.grid.Le, &m.grid.own_Le, &unused, 1.f, ColorUsage::Illuminant);  // "scale" is for the coefficients only
    m.Le_scale = ps.get_float("Lescale", 1.f);
    if (!(m.Le_scale >= 0.f) || !std::isfinite(m.Le_scale))
      ps.fail(*ps.find("Lescale"), "\"Lescale\" must be finite and not negative");
    // pbrt-v4 makes an rgbgrid's Le samples its colour space's illuminant
    // as stored, whose luminance integral is CIE Y's (106.856895), and,
    // unlike every other emitter's Le, does not divide by it: the same
    // "Le" glows that many times brighter in an rgbgrid than in a
    // homogeneous or uniformgrid medium. Files written for it are lit so.
    m.Le_scale *= kPbrtRgbGridLeFactor;
  }
  m.g = ps.get_float("g", 0.f);
  if (!(m.g > -1.f && m.g < 1.f)) ps.fail(*ps.find("g"), "\"g\" must lie strictly between -1 and 1");
  return m;
}

// pbrt-v4's cloud: sigma_a, sigma_s (1 by default; no "scale"), g,
// density, wispiness, frequency and the box p0..p1.
CloudMedium SceneBuilder::cloud(const ParamSet& ps, const Mat4& render_from_medium) {
  CloudMedium m;
  m.sigma_a = checked_coefficient(ps, "sigma_a", ps.get_rgb("sigma_a", ColorUsage::Unbounded).value_or(RGB(1.f)), 1.f);
  m.sigma_s = checked_coefficient(ps, "sigma_s", ps.get_rgb("sigma_s", ColorUsage::Unbounded).value_or(RGB(1.f)), 1.f);
  m.spectra = coefficient_spectra(ps, m.sigma_a, m.sigma_s, 1.f);
  m.g = ps.get_float("g", 0.f);
  if (!(m.g > -1.f && m.g < 1.f)) ps.fail(*ps.find("g"), "\"g\" must lie strictly between -1 and 1");
  m.density = ps.get_float("density", 1.f);
  m.wispiness = ps.get_float("wispiness", 1.f);
  m.frequency = ps.get_float("frequency", 5.f);
  for (const char* name : {"density", "wispiness", "frequency"}) {
    const pbrt::Param* p = ps.find(name);
    if (p && !(std::isfinite(ps.get_float(name, 0.f)) && std::fabs(ps.get_float(name, 0.f)) < 1e6f))
      ps.fail(*p, std::string("\"") + name + "\" must be finite (and below 1e6 in magnitude)");
  }
  GridLayout box;  // the box and transform, checked as a grid's
  grid_layout(ps, render_from_medium, &box);
  m.p0 = box.p0, m.p1 = box.p1;
  m.medium_from_render = box.medium_from_render;
  m.build_proxy(kCloudProxyResolution);
  return m;
}

// pbrt-v4's nanovdb: "filename", the density grid "gridname" (default
// "density"), sigma_a, sigma_s, scale and g; and emission from a
// temperature grid ("temperaturename", default "temperature").
VdbMedium SceneBuilder::vdb_medium(const ParamSet& ps, const Mat4& render_from_medium, const std::string& base_dir) {
  VdbMedium m;
  m.per_density = medium_coefficients(ps, false);
  const pbrt::Param* file = ps.find("filename");
  if (!file) ps.fail("a nanovdb medium needs \"string filename\"");
  const std::string path = resolve_path(base_dir, ps.get_string("filename", ""));
  const std::string grid = ps.get_string("gridname", "density");
  const float det = glm::determinant(render_from_medium);
  if (!std::isfinite(det) || det == 0.f) ps.fail("the medium's transform is singular");
  try {
    m.density = VdbGrid::load(path, grid, glm::inverse(render_from_medium));
    // Emission, as pbrt-v4: a black body at the temperature grid's values
    // (when the file has one), times "Lescale".
    const std::string temperature = ps.get_string("temperaturename", "temperature");
    m.Le_scale = ps.get_float("Lescale", 1.f);
    m.heat.offset = ps.get_float("temperatureoffset", ps.get_float("temperaturecutoff", 0.f));
    m.heat.scale = ps.get_float("temperaturescale", 1.f);
    if (!std::isfinite(m.Le_scale) || !std::isfinite(m.heat.offset) || !std::isfinite(m.heat.scale))
      ps.fail("\"Lescale\", \"temperatureoffset\" and \"temperaturescale\" must be finite");
    if (m.Le_scale > 0.f && VdbGrid::has_grid(path, temperature)) {
      m.temperature = VdbGrid::load(path, temperature, glm::inverse(render_from_medium));
      float largest = 0.f;  // |sample|, infinity for a background that is not zero
      for (float t : m.temperature.block_maxima()) largest = std::max(largest, t);
      m.heat.tabulate(largest);
    }
  } catch (const std::runtime_error& e) {
    if (dynamic_cast<const InputError*>(&e)) throw;
    ps.fail(*file, "\"" + printable(path) + "\" " + e.what());
  }
  return m;
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
  camera_medium_named_later_ = !name.empty() && !named_media_.count(name);
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
  // Read here, since the camera's medium is looked up once the scene is
  // read; pbrt-v4 looks it up at the Camera and stops.
  if (camera_medium_named_later_)
    warn(camera_medium_where_, "the camera stands in medium \"" + printable(camera_medium_) +
                                   "\", named by a MakeNamedMedium after the Camera: pbrt-v4 refuses this file "
                                   "(name the medium before the Camera)");
}

namespace {

// The render-space box around the shapes that have medium h inside them,
// when they alone bound it: h is not the camera's medium, nor the outside
// of any shape, nor on a shape of an instance, a curve or a patch. Else
// false (the caller takes the scene's bounds).
bool enclosing_box(const Scene& sc, MediumHandle h, Vec3* lo, Vec3* hi) {
  if (sc.media.camera == h) return false;
  const ShapePools& shapes = sc.shapes;
  *lo = Vec3(kInfinity), *hi = Vec3(-kInfinity);
  bool any = false;
  for (size_t g = 0; g < shapes.geometries.size(); ++g) {
    const Geometry& geom = shapes.geometries[g];
    if (!geom.media.transition() || (geom.media.inside != h && geom.media.outside != h)) continue;
    if (geom.media.outside == h || shapes.in_prototype[g]) return false;
    Vec3 a, b;
    switch (geom.kind) {
      case ShapeKind::Mesh: {
        const TriangleMesh& m = shapes.meshes[geom.index];
        a = Vec3(kInfinity), b = Vec3(-kInfinity);
        for (uint32_t v = 0; v < m.vertex_count; ++v) a = glm::min(a, m.positions[v]), b = glm::max(b, m.positions[v]);
        break;
      }
      case ShapeKind::Sphere: {
        const Sphere& sp = shapes.spheres[geom.index];
        a = sp.center - Vec3(sp.radius), b = sp.center + Vec3(sp.radius);
        break;
      }
      case ShapeKind::Quadric: quadric_bounds(shapes.quadrics[geom.index], &a, &b); break;
      default: return false;
    }
    *lo = glm::min(*lo, a), *hi = glm::max(*hi, b);
    any = true;
  }
  return any;
}

}  // namespace

// Each emissive medium becomes a light (light/volume_light.h). A
// homogeneous one samples the box of the shapes around it, or of the whole
// scene when they do not bound it.
void SceneBuilder::volume_lights() {
  for (MediumHandle h : scene_.media.emissive_media) {
    Vec3 lo = scene_.bounds_lo, hi = scene_.bounds_hi;
    if (Vec3 a, b; enclosing_box(scene_, h, &a, &b)) lo = glm::max(lo, a), hi = glm::min(hi, b);
    if (h.kind() == MediumKind::Homogeneous && !glm::all(glm::lessThan(lo, hi))) continue;  // no room to emit in
    VolumeLight v;
    if (make_volume_light(scene_.media, h, lo, hi, &v)) scene_.lights.volume.push_back(std::move(v));
  }
}

}  // namespace lantern
