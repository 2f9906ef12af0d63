#include "texture/image.h"

#include "texture/image_io_module.h"

namespace lantern {

bool TextureImage::remap(int* x, int* y, WrapMode wrap) const {
  switch (wrap) {
    case WrapMode::Repeat:
      *x %= width;
      *y %= height;
      if (*x < 0) *x += width;
      if (*y < 0) *y += height;
      return true;
    case WrapMode::Clamp:
      *x = glm::clamp(*x, 0, width - 1);
      *y = glm::clamp(*y, 0, height - 1);
      return true;
    case WrapMode::Black:
      return *x >= 0 && *x < width && *y >= 0 && *y < height;
    case WrapMode::OctahedralSphere:
      // Crossing an edge of the octahedral square lands on the mirrored
      // edge, upside down.
      if (*x < 0) {
        *x = -*x - 1;
        *y = height - 1 - *y;
      } else if (*x >= width) {
        *x = 2 * width - 1 - *x;
        *y = height - 1 - *y;
      }
      if (*y < 0) {
        *x = width - 1 - *x;
        *y = -*y - 1;
      } else if (*y >= height) {
        *x = width - 1 - *x;
        *y = 2 * height - 1 - *y;
      }
      *x = glm::clamp(*x, 0, width - 1);
      *y = glm::clamp(*y, 0, height - 1);
      return true;
  }
  return false;
}

RGB TextureImage::rgb_at(int x, int y, WrapMode wrap) const {
  if (!remap(&x, &y, wrap)) return RGB(0.f);
  return texels[size_t(y) * size_t(width) + size_t(x)];
}

float TextureImage::float_at(int x, int y, WrapMode wrap) const {
  if (!remap(&x, &y, wrap)) return 0.f;
  size_t i = size_t(y) * size_t(width) + size_t(x);
  if (channels == 4) return alpha[i];
  const RGB& c = texels[i];
  return channels == 1 ? c[0] : (c[0] + c[1] + c[2]) / 3.f;
}

template <class T, class Fetch>
T TextureImage::bilerp(Vec2 st, Fetch&& fetch) const {
  float x = st.x * float(width) - 0.5f, y = st.y * float(height) - 0.5f;
  float fx = std::floor(x), fy = std::floor(y);
  if (!(std::fabs(fx) < 1e9f) || !(std::fabs(fy) < 1e9f)) return T(0.f);
  int ix = int(fx), iy = int(fy);
  float dx = x - fx, dy = y - fy;
  return (1 - dx) * (1 - dy) * fetch(ix, iy) + dx * (1 - dy) * fetch(ix + 1, iy) + (1 - dx) * dy * fetch(ix, iy + 1) +
         dx * dy * fetch(ix + 1, iy + 1);
}

RGB TextureImage::lookup_rgb(Vec2 st, ImageFilter filter, WrapMode wrap) const {
  if (filter == ImageFilter::Point) {
    float x = std::round(st.x * float(width) - 0.5f), y = std::round(st.y * float(height) - 0.5f);
    if (!(std::fabs(x) < 1e9f) || !(std::fabs(y) < 1e9f)) return RGB(0.f);
    return rgb_at(int(x), int(y), wrap);
  }
  return bilerp<RGB>(st, [&](int x, int y) { return rgb_at(x, y, wrap); });
}

float TextureImage::lookup_float(Vec2 st, ImageFilter filter, WrapMode wrap) const {
  if (filter == ImageFilter::Point) {
    // pbrt-v4 reads the first channel for point lookups.
    float x = std::round(st.x * float(width) - 0.5f), y = std::round(st.y * float(height) - 0.5f);
    if (!(std::fabs(x) < 1e9f) || !(std::fabs(y) < 1e9f)) return 0.f;
    return rgb_at(int(x), int(y), wrap)[0];
  }
  return bilerp<float>(st, [&](int x, int y) { return float_at(x, y, wrap); });
}

TextureImage load_texture_image(const std::string& path, ColorEncoding encoding) {
  return image_io_module().load_texture_image(path, encoding);
}

}  // namespace lantern
