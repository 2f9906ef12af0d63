// Images for textures and environment lights: linear RGB texels (plus the
// alpha channel when the file has one), looked up with pbrt-v4's wrap modes
// and point or bilinear filtering.
#pragma once

#include <string>
#include <vector>

#include "math/common.h"
#include "texture/color_encoding.h"

namespace lantern {

enum class WrapMode : uint8_t { Repeat, Black, Clamp, OctahedralSphere };
// Trilinear and EWA filter over the footprint through the texture cache;
// resident images read them as bilinear.
enum class ImageFilter : uint8_t { Point, Bilinear, Trilinear, EWA };

struct TextureImage {
  int width = 0, height = 0;
  int channels = 3;         // in the file: 1 (grey), 3 (RGB) or 4 (RGBA)
  std::vector<RGB> texels;  // linear RGB, row 0 at the top; grey files repeat it
  std::vector<float> alpha; // RGBA files only
  std::string filename;
  float mean = 0.f;         // of the texels over their channels (light power)
  // Of any texel's channels and alpha, for TexturePools::range (as set by
  // load_texture_image; empty, so unknown, otherwise).
  float least = kInfinity, greatest = -kInfinity;

  // pbrt-v4's lookups: st with t = 0 at the top row. A float lookup reads a
  // grey file's value, the mean of RGB, or (filtered) an RGBA file's alpha.
  RGB lookup_rgb(Vec2 st, ImageFilter filter, WrapMode wrap) const;
  float lookup_float(Vec2 st, ImageFilter filter, WrapMode wrap) const;

 private:
  // Maps (x, y) into the image by the wrap mode; false where it is black.
  bool remap(int* x, int* y, WrapMode wrap) const;
  RGB rgb_at(int x, int y, WrapMode wrap) const;
  float float_at(int x, int y, WrapMode wrap) const;
  template <class T, class Fetch>
  T bilerp(Vec2 st, Fetch&& fetch) const;
};

// Loads an image (through the image module, imageio/); `encoding` decodes
// integer formats.
// Throws InputError naming the file for unreadable, empty, huge or
// non-finite images.
TextureImage load_texture_image(const std::string& path, ColorEncoding encoding);

}  // namespace lantern
