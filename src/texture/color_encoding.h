// How the values of integer (8- and 16-bit) image files become linear, and
// which encoding applies to a file: pbrt-v4's rules, which go by the file's
// extension. Header-only: the image module (imageio/) applies them as it
// decodes, and the scene builder picks the default.
#pragma once

#include <cctype>
#include <cmath>
#include <cstdint>
#include <string>

namespace lantern {

// How integer-valued files encode their values; float files are always
// linear.
struct ColorEncoding {
  enum Kind : uint8_t { Linear, SRGB, Gamma } kind = SRGB;
  float gamma = 2.2f;
  float to_linear(float v) const {
    switch (kind) {
      case Linear: return v;
      case Gamma: return std::pow(max_num(v, 0.f), gamma);
      case SRGB: break;
    }
    return v <= 0.04045f ? v / 12.92f : std::pow((v + 0.055f) / 1.055f, 2.4f);
  }
};

// The file's extension in lower case, "" without one.
inline std::string lowercase_extension(const std::string& filename) {
  auto dot = filename.find_last_of('.');
  auto slash = filename.find_last_of("/\\");
  if (dot == std::string::npos || (slash != std::string::npos && dot < slash)) return "";
  std::string ext = filename.substr(dot + 1);
  for (char& c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
  return ext;
}

// pbrt-v4's default for an image texture without "encoding": sRGB for PNG
// files, linear for every other format.
inline ColorEncoding default_texture_encoding(const std::string& filename) {
  return ColorEncoding{lowercase_extension(filename) == "png" ? ColorEncoding::SRGB : ColorEncoding::Linear};
}

// The encoding an integer file's values are decoded with, given the one the
// scene asks for. pbrt-v4 honours `encoding` only for PNG; every other 8-bit
// file is sRGB whatever `encoding` says. `bits` is 8 or 16 (per channel).
// docs/textures.md tabulates the rule per format.
inline ColorEncoding file_encoding(const std::string& filename, int bits, ColorEncoding requested) {
  const std::string ext = lowercase_extension(filename);
  // pbrt-v4's own PNG reader decodes 8 and 16 bits by `encoding`.
  if (ext == "png") return requested;
  // Every other integer file goes to pbrt-v4's 8-bit reader (stb_image),
  // which marks its pixels sRGB, and reduces 16-bit PNM and PSD files to 8
  // bits first. Formats it cannot read (TIFF, WebP, ...) follow the same
  // rule at 8 bits; at 16 bits they keep `encoding`, as a 16-bit file is
  // usually linear data and pbrt-v4 has no image of it to match.
  const bool stb_sixteen_bit = ext == "pnm" || ext == "ppm" || ext == "pgm" || ext == "psd";
  if (bits <= 8 || stb_sixteen_bit) return ColorEncoding{ColorEncoding::SRGB};
  return requested;
}

}  // namespace lantern
