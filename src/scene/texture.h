// Reflectance textures: a constant or an image looked up by (u, v), with
// pbrt's uv mapping parameters. Images live in one pool shared by materials
// and the environment light.
#pragma once

#include <string>
#include <vector>

#include "math/common.h"

namespace lantern {

struct TextureImage {
  int width = 0, height = 0;
  std::vector<RGB> texels;  // linear RGB, row 0 at the top
  std::string filename;

  RGB texel(int x, int y) const;  // wraps around (repeat)
  RGB bilinear(Vec2 st) const;    // st in [0,1)^2, t = 0 at the top row
};

struct RGBTexture {
  RGB value{0.5f};
  int32_t image = -1;  // index into TexturePools::images, or -1 for a constant
  float su = 1.f, sv = 1.f, du = 0.f, dv = 0.f;
  float scale = 1.f;
  bool invert = false;
};

struct TexturePools {
  std::vector<TextureImage> images;

  RGB evaluate(const RGBTexture& t, Vec2 uv) const {
    if (t.image < 0) return t.value;
    // pbrt-v4 flips t so that v = 0 is the bottom of the image.
    Vec2 st(t.su * uv.x + t.du, 1.f - (t.sv * uv.y + t.dv));
    RGB c = images[size_t(t.image)].bilinear(st) * t.scale;
    if (t.invert) c = glm::max(RGB(0.f), RGB(1.f) - c);
    return glm::clamp(c, RGB(0.f), RGB(1.f));
  }
};

// Loads an image through OpenImageIO as linear RGB. 8-bit images are taken
// as sRGB-encoded unless `linear` says otherwise. Throws InputError.
TextureImage load_texture_image(const std::string& path, bool force_linear, bool force_srgb);

}  // namespace lantern
