// A directive's parameter list: "type name" [values], type-checked on read.
// Every parameter remembers whether it was read, so the parser can warn
// about the ones a directive ignored.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "color/color_space.h"
#include "color/piecewise_linear_spectrum.h"
#include "lantern/error.h"
#include "math/common.h"

namespace lantern::pbrt {

struct Param {
  std::string type;  // as written: "float", "rgb", "point3", ...
  std::string name;
  std::vector<double> numbers;
  std::vector<std::string> strings;
  std::vector<bool> bools;
  SourceLocation where;
  mutable bool used = false;
};

// What a colour parameter describes: pbrt converts spectra differently for
// reflectances (bounded by 1), illuminants and unbounded quantities (eta, k).
enum class ColorUsage { Reflectance, Illuminant, Unbounded };

class ParamSet {
 public:
  std::vector<Param> params;
  SourceLocation where;        // of the directive
  std::string directive;      // e.g. Shape "sphere", for messages
  WarningSink* warn = nullptr;
  // The directive's kind ("shape", "material", "camera", ...:
  // pbrt/known_params.h), whose parameter names pbrt-v4 and pbrt-v3 know;
  // null: any name is known.
  const char* kind = nullptr;
  // --lenient: a parameter neither knows is a warning, not an error.
  bool lenient = false;
  std::string base_dir;       // relative file names (spectrum files) are resolved against it
  // The ColorSpace in effect at the directive: its "rgb" values are in it
  // (null: sRGB).
  const ColorSpace* color_space = nullptr;

  const Param* find(const std::string& name) const;
  bool has(const std::string& name) const { return find(name) != nullptr; }

  float get_float(const std::string& name, float def) const;
  int get_int(const std::string& name, int def) const;
  bool get_bool(const std::string& name, bool def) const;
  std::string get_string(const std::string& name, const std::string& def) const;
  std::vector<float> get_floats(const std::string& name) const;
  std::vector<int> get_ints(const std::string& name) const;
  std::vector<Vec3> get_point3s(const std::string& name) const;  // point3, vector3, normal
  std::vector<Vec2> get_point2s(const std::string& name) const;
  Vec3 get_point3(const std::string& name, Vec3 def) const;
  // rgb / color / spectrum / blackbody, in linear sRGB (the renderer's
  // colours); nullopt when absent. An "rgb" value of another colour space
  // is converted: a reflectance or unbounded value with its white adapted
  // to sRGB's (so (1, 1, 1) stays white), an illuminant as the same light;
  // what falls outside sRGB's gamut is clamped, with a warning. A sampled
  // spectrum (pairs or a file) becomes the colour a spectral renderer shows
  // for it: a reflectance or unbounded value under D65, an illuminant
  // normalised to luminance 1 (as pbrt-v4 normalises light spectra).
  std::optional<RGB> get_rgb(const std::string& name, ColorUsage usage) const;
  // Colour c of p, in this set's colour space, in linear sRGB as get_rgb
  // converts it; `warn_gamut` false: without the warning for colours
  // outside sRGB's gamut (a second look at a colour get_rgb has read).
  // *outside, if given, says whether c lay outside it (and was clamped).
  RGB to_srgb(const Param& p, const RGB& c, ColorUsage usage, bool warn_gamut = true, bool* outside = nullptr) const;
  // A "spectrum" parameter given by samples, inline or in a file, or a named
  // metal's measured eta or k; nullopt for any other form or when absent.
  std::optional<PiecewiseLinearSpectrum> get_sampled_spectrum(const std::string& name) const;
  // An emitter's colour given as a spectrum (a "blackbody" temperature, a
  // "spectrum" file or pairs): the spectrum, and its colour at luminance 1
  // (what get_rgb gives, without pbrt-v3's blackbody scale). nullopt for
  // any other form.
  struct EmissionSpectrum {
    PiecewiseLinearSpectrum spectrum;
    RGB rgb;
  };
  std::optional<EmissionSpectrum> get_emission_spectrum(const std::string& name) const;
  // Name of a texture parameter ("texture reflectance" "tex"), if given that way.
  std::optional<std::string> get_texture(const std::string& name) const;

  [[noreturn]] void fail(const Param& p, const std::string& what) const;
  [[noreturn]] void fail(const std::string& what) const;
  // Each parameter no lookup asked for: one that pbrt-v4 or pbrt-v3 knows
  // for the directive's kind is a warning ("not used"); any other is an
  // error, as pbrt-v4 stops on a parameter it does not use, naming the word
  // meant where one is a letter or two away ("float fovv": "fov"), or a
  // warning when lenient.
  void warn_unused() const;

 private:
  mutable std::vector<std::string> missed_;  // names looked up and not given (for warn_unused)
  const Param& expect(const Param& p, std::initializer_list<const char*> types, const char* expected) const;
};

// Colour of a blackbody emitter at the given temperature, in linear sRGB,
// normalised to luminance 1 (pbrt normalises light spectra photometrically).
RGB blackbody_rgb(float kelvin);
// A named spectrum of pbrt-v4 (metal-Cu-eta, glass-BK7, ...) as RGB.
std::optional<RGB> named_spectrum_rgb(const std::string& name);
// A named metal's measured eta or k (metal-Au-k, ...) as samples; nullopt
// for other names.
std::optional<PiecewiseLinearSpectrum> named_sampled_spectrum(const std::string& name);

}  // namespace lantern::pbrt
