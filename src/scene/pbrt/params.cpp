#include "scene/pbrt/params.h"

#include "color/cie1931.h"
#include "color/cie_daylight.h"
#include "color/cie_fluorescent.h"
#include "color/glass.h"
#include "color/optical_constants.h"
#include "color/sigmoid_spectrum.h"
#include "math/edit_distance.h"
#include "scene/pbrt/known_params.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <stdexcept>

namespace lantern::pbrt {

const Param* ParamSet::find(const std::string& name) const {
  for (const Param& p : params)
    if (p.name == name) {
      p.used = true;
      return &p;
    }
  // Each name once: a set read for many shapes (an area light's) must not
  // grow with them.
  if (!params.empty() && std::find(missed_.begin(), missed_.end(), name) == missed_.end()) missed_.push_back(name);
  return nullptr;
}

void ParamSet::fail(const Param& p, const std::string& what) const {
  throw InputError(p.where, directive + ": parameter \"" + printable(p.name) + "\": " + what);
}
void ParamSet::fail(const std::string& what) const { throw InputError(where, directive + ": " + what); }

void ParamSet::warn_unused() const {
  for (const Param& p : params) {
    if (p.used) continue;
    const std::string said = "parameter \"" + printable(p.type + " " + p.name) + "\"";
    if (!kind || is_known_parameter(kind, p.name)) {
      // pbrt reads it (for this directive or another of its kind): a
      // construct Lantern does not model, the image otherwise the same.
      if (warn && *warn) (*warn)(p.where.str() + ": warning: " + directive + ": " + said + " is not supported and was ignored");
      continue;
    }
    // A near miss: one letter off in names under eight letters, two from
    // eight; a name the directive looked up and was not given first.
    const size_t reach = p.name.size() >= 8 ? 2 : 1;
    std::string meant = nearest_word(p.name, missed_, reach);
    if (meant.empty()) meant = nearest_word(p.name, known_parameters(kind), reach);
    const std::string what = "unknown " + said + ": neither pbrt-v4 nor pbrt-v3 reads it" +
                             (meant.empty() ? std::string() : "; did you mean \"" + printable(meant) + "\"?");
    if (!lenient) throw InputError(p.where, directive + ": " + what + " (--lenient ignores it with a warning)");
    if (warn && *warn) (*warn)(p.where.str() + ": warning: " + directive + ": " + what + "; ignored (--lenient)");
  }
}

const Param& ParamSet::expect(const Param& p, std::initializer_list<const char*> types, const char* expected) const {
  for (const char* t : types)
    if (p.type == t) return p;
  fail(p, "has type \"" + printable(p.type) + "\", expected " + expected);
}

static void expect_count(const ParamSet& ps, const Param& p, size_t have, size_t multiple) {
  if (have == 0) ps.fail(p, "has no values");
  if (have % multiple != 0)
    ps.fail(p, "has " + std::to_string(have) + " values, expected a multiple of " + std::to_string(multiple));
}

float ParamSet::get_float(const std::string& name, float def) const {
  const Param* p = find(name);
  if (!p) return def;
  expect(*p, {"float"}, "\"float\"");
  if (p->numbers.size() != 1) fail(*p, "expected exactly one value, got " + std::to_string(p->numbers.size()));
  return float(p->numbers[0]);
}

int ParamSet::get_int(const std::string& name, int def) const {
  const Param* p = find(name);
  if (!p) return def;
  expect(*p, {"integer"}, "\"integer\"");
  if (p->numbers.size() != 1) fail(*p, "expected exactly one value, got " + std::to_string(p->numbers.size()));
  double v = p->numbers[0];
  if (v != std::floor(v) || std::fabs(v) > 2147483647.0) fail(*p, "expected an integer value");
  return int(v);
}

bool ParamSet::get_bool(const std::string& name, bool def) const {
  const Param* p = find(name);
  if (!p) return def;
  expect(*p, {"bool"}, "\"bool\"");
  if (p->bools.size() != 1) fail(*p, "expected exactly one value (true or false)");
  return p->bools[0];
}

std::string ParamSet::get_string(const std::string& name, const std::string& def) const {
  const Param* p = find(name);
  if (!p) return def;
  expect(*p, {"string"}, "\"string\"");
  if (p->strings.size() != 1) fail(*p, "expected exactly one string");
  return p->strings[0];
}

std::vector<float> ParamSet::get_floats(const std::string& name) const {
  const Param* p = find(name);
  if (!p) return {};
  expect(*p, {"float"}, "\"float\"");
  return std::vector<float>(p->numbers.begin(), p->numbers.end());
}

std::vector<int> ParamSet::get_ints(const std::string& name) const {
  const Param* p = find(name);
  if (!p) return {};
  expect(*p, {"integer"}, "\"integer\"");
  std::vector<int> out;
  out.reserve(p->numbers.size());
  for (double v : p->numbers) {
    if (v != std::floor(v) || std::fabs(v) > 2147483647.0) fail(*p, "expected integer values");
    out.push_back(int(v));
  }
  return out;
}

std::vector<Vec3> ParamSet::get_point3s(const std::string& name) const {
  const Param* p = find(name);
  if (!p) return {};
  expect(*p, {"point3", "point", "vector3", "vector", "normal", "normal3"}, "\"point3\", \"vector3\" or \"normal\"");
  expect_count(*this, *p, p->numbers.size(), 3);
  std::vector<Vec3> out(p->numbers.size() / 3);
  for (size_t i = 0; i < out.size(); ++i)
    out[i] = Vec3(float(p->numbers[3 * i]), float(p->numbers[3 * i + 1]), float(p->numbers[3 * i + 2]));
  return out;
}

std::vector<Vec2> ParamSet::get_point2s(const std::string& name) const {
  const Param* p = find(name);
  if (!p) return {};
  expect(*p, {"point2", "vector2", "float"}, "\"point2\"");
  expect_count(*this, *p, p->numbers.size(), 2);
  std::vector<Vec2> out(p->numbers.size() / 2);
  for (size_t i = 0; i < out.size(); ++i) out[i] = Vec2(float(p->numbers[2 * i]), float(p->numbers[2 * i + 1]));
  return out;
}

Vec3 ParamSet::get_point3(const std::string& name, Vec3 def) const {
  const Param* p = find(name);
  if (!p) return def;
  auto v = get_point3s(name);
  if (v.size() != 1) fail(*p, "expected exactly three values");
  return v[0];
}

std::optional<std::string> ParamSet::get_texture(const std::string& name) const {
  const Param* p = find(name);
  if (!p || p->type != "texture") return std::nullopt;
  if (p->strings.size() != 1) fail(*p, "expected exactly one texture name");
  return p->strings[0];
}

RGB ParamSet::to_srgb(const Param& p, const RGB& c, ColorUsage usage, bool warn_gamut, bool* outside) const {
  const Matrix3d m = rgb_conversion(*color_space, ColorSpace::srgb(), usage != ColorUsage::Illuminant);
  RGB r;
  for (size_t i = 0; i < 3; ++i) r[int(i)] = float(m[i][0] * c[0] + m[i][1] * c[1] + m[i][2] * c[2]);
  const bool out = min_component(r) < -1e-5f * max_component(r);
  if (outside) *outside = out;
  if (warn_gamut && out && warn && *warn)
    (*warn)(p.where.str() + ": warning: " + directive + ": \"" + printable(p.name) + "\" (" + std::string(color_space->name) +
            ") lies outside sRGB's gamut, in which the RGB renderer works: there its negative part is clamped "
            "(with --spectral a material's, an emitter's or a medium's colour of its own space keeps it)");
  return max(r, RGB(0.f));
}

std::optional<RGB> ParamSet::get_rgb(const std::string& name, ColorUsage usage) const {
  const Param* p = find(name);
  if (!p) return std::nullopt;
  if (p->type == "rgb" || p->type == "color") {
    if (p->numbers.size() != 3) fail(*p, "expected three values (r g b), got " + std::to_string(p->numbers.size()));
    RGB c(float(p->numbers[0]), float(p->numbers[1]), float(p->numbers[2]));
    if (c[0] < 0.f || c[1] < 0.f || c[2] < 0.f) fail(*p, "RGB values must not be negative");
    if (color_space && color_space != &ColorSpace::srgb()) c = to_srgb(*p, c, usage);
    if (usage == ColorUsage::Reflectance && max_component(c) > 1.f && warn && *warn)
      (*warn)(p->where.str() + ": warning: " + directive + ": reflectance \"" + printable(name) + "\" exceeds 1 and was clamped");
    if (usage == ColorUsage::Reflectance) c = min(c, RGB(1.f));
    return c;
  }
  if (p->type == "blackbody") {
    // pbrt-v4: the temperature; pbrt-v3: the temperature and a scale,
    // which pbrt-v4's --upgrade moves into the light's "scale".
    if (p->numbers.size() != 1 && p->numbers.size() != 2)
      fail(*p, "expected a temperature in kelvin (pbrt-v3: a temperature and a scale)");
    const float scale = p->numbers.size() == 2 ? float(p->numbers[1]) : 1.f;
    if (!(scale >= 0.f) || !std::isfinite(scale)) fail(*p, "the blackbody's scale must be a finite number >= 0");
    return blackbody_rgb(float(p->numbers[0])) * scale;
  }
  if (p->type == "spectrum") {
    if (!p->strings.empty())
      if (auto c = named_spectrum_rgb(p->strings[0])) return *c;
    if (p->strings.empty() && p->numbers.size() == 1) return RGB(float(p->numbers[0]));
    const std::optional<PiecewiseLinearSpectrum> sampled = get_sampled_spectrum(name);
    if (!sampled) fail(*p, "expected a value, (wavelength, value) pairs, a named spectrum or a spectrum file");
    if (usage == ColorUsage::Illuminant) return illuminant_rgb(*sampled);
    RGB c = reflectance_rgb(*sampled);
    if (usage == ColorUsage::Reflectance) {
      if (max_component(c) > 1.f && warn && *warn)
        (*warn)(p->where.str() + ": warning: " + directive + ": reflectance \"" + printable(name) + "\" exceeds 1 and was clamped");
      c = clamp(c, RGB(0.f), RGB(1.f));
    }
    return c;
  }
  if (p->type == "float" && usage == ColorUsage::Unbounded && p->numbers.size() == 1)
    return RGB(float(p->numbers[0]));
  fail(*p, "has type \"" + p->type + "\", expected \"rgb\", \"spectrum\" or \"blackbody\"");
}

std::optional<ParamSet::EmissionSpectrum> ParamSet::get_emission_spectrum(const std::string& name) const {
  const Param* p = find(name);
  if (!p) return std::nullopt;
  if (p->type == "blackbody") {
    (void)get_rgb(name, ColorUsage::Illuminant);  // (its checks)
    const float kelvin = float(p->numbers[0]);
    return EmissionSpectrum{blackbody_spectrum(kelvin), blackbody_rgb(kelvin)};
  }
  if (p->type != "spectrum" || (!p->strings.empty() && named_spectrum_rgb(p->strings[0])) ||
      (p->strings.empty() && p->numbers.size() == 1))
    return std::nullopt;  // a named metal or glass, or one number: as colour
  std::optional<PiecewiseLinearSpectrum> s = get_sampled_spectrum(name);
  if (!s) return std::nullopt;
  const RGB rgb = illuminant_rgb(*s);
  return EmissionSpectrum{std::move(*s), rgb};
}

std::optional<PiecewiseLinearSpectrum> ParamSet::get_sampled_spectrum(const std::string& name) const {
  const Param* p = find(name);
  if (!p || p->type != "spectrum") return std::nullopt;
  if (p->strings.empty()) {
    if (p->numbers.size() < 2) return std::nullopt;
    try {
      return spectrum_from_pairs(p->numbers);
    } catch (const std::invalid_argument& e) {
      fail(*p, e.what());
    }
  }
  if (p->strings.size() != 1) fail(*p, "expected one spectrum name or file");
  const std::string& s = p->strings[0];
  if (auto named = named_sampled_spectrum(s)) return named;  // a named metal's measured constants, or a glass
  // Anything else names a spectrum file, relative to the scene's folder.
  std::filesystem::path file(s);
  if (file.is_relative() && !base_dir.empty()) file = std::filesystem::path(base_dir) / file;
  std::error_code ec;
  if (!std::filesystem::is_regular_file(file, ec))
    fail(*p, "\"" + printable(s) + "\" is neither a named spectrum (metal-{Cu,Au,Ag,Al,CuZn,MgO,TiO2}-{eta,k}, "
             "glass-{BK7,BAF10,FK51A,LASF9,F5,F10,F11}, stdillum-{A,D50,D65,F1..F12}, illum-acesD60; pbrt-v4's camera "
             "curves are not included: give them as a spectrum file) nor a spectrum file (" + printable(file.string()) + " not found)");
  try {
    return read_spectrum_file(file.string());
  } catch (const InputError& e) {
    fail(*p, e.what());
  }
}

namespace {

// pbrt-v4's stdillum-D65 (CIE 015:2004, Table T.1, color/cie1931.h),
// stdillum-D50 and illum-acesD60 (CIE daylight, color/cie_daylight.h) and
// stdillum-A, which CIE 015:2004 defines by its formula (Planck's law at
// 2848 K with the second radiation constant 1.435e7 nm K, 100 at 560 nm),
// and the fluorescent stdillum-F1 to F12 (color/cie_fluorescent.h).
// As lights, their spectra are normalised like any other light's.
// n for "stdillum-Fn" (1 to 12), else 0.
int fluorescent_number(const std::string& name) {
  for (int n = 1; n <= 12; ++n)
    if (name == "stdillum-F" + std::to_string(n)) return n;
  return 0;
}

PiecewiseLinearSpectrum standard_illuminant(const std::string& name) {
  PiecewiseLinearSpectrum out;
  for (int nm = int(kLambdaMin); nm <= int(kLambdaMax); ++nm) {
    const double l = double(nm);
    out.nm.push_back(l);
    if (name == "stdillum-D65") {
      out.value.push_back(double(cie_d65(float(nm))));
    } else if (name == "stdillum-D50") {
      out.value.push_back(double(cie_d50(float(nm))));
    } else if (name == "illum-acesD60") {
      out.value.push_back(double(aces_d60(float(nm))));
    } else if (const int f = fluorescent_number(name)) {
      out.value.push_back(double(cie_fluorescent(f, float(nm))));
    } else {
      constexpr double c2 = 1.435e7, T = 2848.0;
      out.value.push_back(100.0 * std::pow(560.0 / l, 5.0) * std::expm1(c2 / (T * 560.0)) / std::expm1(c2 / (T * l)));
    }
  }
  return out;
}

}  // namespace

std::optional<PiecewiseLinearSpectrum> named_sampled_spectrum(const std::string& s) {
  if (const std::optional<SellmeierGlass> glass = named_glass(s)) {  // its formula at every nanometre
    PiecewiseLinearSpectrum out;
    for (int nm = int(kLambdaMin); nm <= int(kLambdaMax); ++nm) {
      out.nm.push_back(double(nm));
      out.value.push_back(glass->index(double(nm)));
    }
    return out;
  }
  if (s == "stdillum-D65" || s == "stdillum-D50" || s == "stdillum-A" || s == "illum-acesD60" || fluorescent_number(s))
    return standard_illuminant(s);
  if (!s.starts_with("metal-")) return std::nullopt;
  const size_t dash = s.rfind('-');
  const std::string metal = s.substr(6, dash > 6 ? dash - 6 : 0), part = s.substr(dash + 1);
  const auto table = optical_constants(metal);
  if (table.empty() || (part != "eta" && part != "k")) return std::nullopt;
  PiecewiseLinearSpectrum out;
  for (const OpticalConstant& row : table) {
    out.nm.push_back(row.nm);
    out.value.push_back(part == "eta" ? row.n : row.k);
  }
  return out;
}

// A black body's colour: its spectrum against the tabulated CIE 1931
// observer (color/cie1931.h), luminance 1, in linear sRGB (negative
// components, below 1900 K or so, clamped).
RGB blackbody_rgb(float kelvin) {
  const Vec3 xyz = blackbody_xyz(kelvin);
  if (xyz.y <= 0.f) return RGB(0.f);
  return max(xyz_to_linear_srgb(xyz), RGB(0.f));
}

std::optional<RGB> named_spectrum_rgb(const std::string& name) {
  // metal-<metal>-eta and metal-<metal>-k: the measured spectra reduced to
  // the per-channel conductor that matches them (color/optical_constants.h).
  if (name.starts_with("metal-")) {
    const std::string_view rest = std::string_view(name).substr(6);
    const size_t dash = rest.rfind('-');
    if (dash == std::string_view::npos) return std::nullopt;
    const std::string_view part = rest.substr(dash + 1);
    if (part != "eta" && part != "k") return std::nullopt;
    const auto conductor = named_conductor_rgb(rest.substr(0, dash));
    if (!conductor) return std::nullopt;
    return part == "eta" ? conductor->eta : conductor->k;
  }
  // A glass: its index at the helium d line, as catalogues quote it (the
  // spectral renderer reads the whole curve: SceneBuilder::eta_param).
  if (const std::optional<SellmeierGlass> glass = named_glass(name)) return RGB(float(glass->index(kHeliumDLine)));
  return std::nullopt;
}

}  // namespace lantern::pbrt
