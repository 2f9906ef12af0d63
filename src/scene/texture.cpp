#include "scene/texture.h"

#include <OpenImageIO/imageio.h>

#include "lantern/error.h"

namespace lantern {

RGB TextureImage::texel(int x, int y) const {
  x %= width;
  y %= height;
  if (x < 0) x += width;
  if (y < 0) y += height;
  return texels[size_t(y) * size_t(width) + size_t(x)];
}

RGB TextureImage::bilinear(Vec2 st) const {
  float x = st.x * float(width) - 0.5f, y = st.y * float(height) - 0.5f;
  float fx = std::floor(x), fy = std::floor(y);
  if (!std::isfinite(fx) || !std::isfinite(fy)) return RGB(0.f);
  int ix = int(fx), iy = int(fy);
  float dx = x - fx, dy = y - fy;
  return (1 - dx) * (1 - dy) * texel(ix, iy) + dx * (1 - dy) * texel(ix + 1, iy) +
         (1 - dx) * dy * texel(ix, iy + 1) + dx * dy * texel(ix + 1, iy + 1);
}

static float srgb_to_linear(float v) {
  return v <= 0.04045f ? v / 12.92f : std::pow((v + 0.055f) / 1.055f, 2.4f);
}

TextureImage load_texture_image(const std::string& path, bool force_linear, bool force_srgb) {
  auto in = OIIO::ImageInput::open(path);
  if (!in) throw InputError({path, 0, 0}, "cannot read image: " + OIIO::geterror());
  const OIIO::ImageSpec& spec = in->spec();
  if (spec.width <= 0 || spec.height <= 0 || spec.nchannels <= 0 || int64_t(spec.width) * spec.height > (int64_t(1) << 28))
    throw InputError({path, 0, 0}, "image has an unsupported size " + std::to_string(spec.width) + "x" + std::to_string(spec.height));
  int nc = spec.nchannels;
  std::vector<float> data(size_t(spec.width) * size_t(spec.height) * size_t(nc));
  if (!in->read_image(0, 0, 0, nc, OIIO::TypeDesc::FLOAT, data.data()))
    throw InputError({path, 0, 0}, "cannot decode image: " + in->geterror());
  bool eight_bit = spec.format == OIIO::TypeDesc::UINT8 || spec.format == OIIO::TypeDesc::UINT16;
  bool srgb = force_srgb || (!force_linear && eight_bit);
  TextureImage img;
  img.filename = path;
  img.width = spec.width;
  img.height = spec.height;
  img.texels.resize(size_t(spec.width) * size_t(spec.height));
  for (size_t i = 0; i < img.texels.size(); ++i) {
    const float* px = &data[i * size_t(nc)];
    RGB c = nc >= 3 ? RGB(px[0], px[1], px[2]) : RGB(px[0]);
    if (srgb) c = RGB(srgb_to_linear(c.x), srgb_to_linear(c.y), srgb_to_linear(c.z));
    img.texels[i] = glm::max(c, RGB(0.f));
  }
  return img;
}

}  // namespace lantern
