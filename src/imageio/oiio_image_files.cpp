// The image module's image files: the render's output and the images
// compare and info read, through OpenImageIO.
#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <sstream>
#include <stdexcept>

#include "imageio/oiio_module.h"
#include "imageio/replace_file.h"
#include "lantern/error.h"

namespace lantern::oiio {

static bool is_float_format(const std::string& ext) { return ext == ".exr" || ext == ".hdr" || ext == ".pfm"; }

static unsigned char encode_srgb8(float v) {
  if (!(v > 0.f)) return 0;
  v = v <= 0.0031308f ? 12.92f * v : 1.055f * std::pow(v, 1.f / 2.4f) - 0.055f;
  return (unsigned char)std::lround(std::clamp(v, 0.f, 1.f) * 255.f);
}

bool can_write_format(const std::string& path) {
  // An output for the name, not opened: nothing is created.
  return OIIO::ImageOutput::create(path) != nullptr;
}

void write_image(const std::string& path, const Image& image, const ImageMetadata& metadata) {
  const std::string bare = lowercase_extension(path), ext = bare.empty() ? "" : "." + bare;
  bool linear = is_float_format(ext);
  // Keep the real extension on the temporary name: OpenImageIO picks the
  // writer from it.
  std::string tmp = temporary_output(path, std::filesystem::path(path).extension().string());
  auto out = OIIO::ImageOutput::create(tmp);
  if (!out) throw std::runtime_error("cannot write \"" + path + "\": no image writer for extension \"" + ext + "\"");
  // More channels than R, G, B (a gbuffer) go to OpenEXR only, after them.
  const size_t extra = ext == ".exr" ? image.channel_names.size() : 0;
  const int nchannels = 3 + int(extra);
  OIIO::ImageSpec spec(image.width, image.height, nchannels, linear ? OIIO::TypeDesc::FLOAT : OIIO::TypeDesc::UINT8);
  if (extra > 0) {
    spec.channelnames = {"R", "G", "B"};
    for (const std::string& n : image.channel_names) spec.channelnames.push_back(n);
  }
  bool half = false;
  for (const auto& [k, v] : metadata) {
    if (k == "chromaticities") {
      // Eight numbers, OpenEXR's standard attribute (written where the
      // format has it).
      float c[8] = {};
      std::istringstream in(v);
      for (float& x : c) in >> x;
      if (linear && in) spec.attribute(k, OIIO::TypeDesc(OIIO::TypeDesc::FLOAT, 8), c);
    } else if (k == "pixelbounds") {
      // The image is part of a larger one: its origin there and that one's
      // size (OpenEXR's data window inside its display window).
      std::istringstream in(v);
      int x0 = 0, y0 = 0, w = 0, h = 0;
      in >> x0 >> y0 >> w >> h;
      if (linear && in)
        spec.x = x0, spec.y = y0, spec.full_x = 0, spec.full_y = 0, spec.full_width = w, spec.full_height = h;
    } else if (k == "half") {
      // Film "savefp16": 16-bit floats in an OpenEXR file.
      half = v == "true" && ext == ".exr";
    } else {
      spec.attribute(k, v);
    }
  }
  if (half) spec.set_format(OIIO::TypeDesc::HALF);
  if (!linear) spec.attribute("oiio:ColorSpace", "sRGB");
  if (!out->open(tmp, spec)) throw std::runtime_error("cannot write \"" + path + "\": " + out->geterror());
  bool ok;
  if (linear) {
    std::vector<float> pixels;
    const float* data = image.rgb.data();
    if (extra > 0) {
      const size_t n = size_t(image.width) * size_t(image.height);
      pixels.resize(n * size_t(nchannels));
      for (size_t i = 0; i < n; ++i) {
        std::copy(&image.rgb[3 * i], &image.rgb[3 * i] + 3, &pixels[i * size_t(nchannels)]);
        std::copy(&image.channels[i * extra], &image.channels[i * extra] + extra, &pixels[i * size_t(nchannels) + 3]);
      }
      data = pixels.data();
    }
    if (half) {
      // Above half's largest value a converted pixel would be infinite:
      // kept at that value instead.
      if (pixels.empty()) pixels.assign(image.rgb.begin(), image.rgb.end());
      for (float& v : pixels) v = std::clamp(v, -65504.f, 65504.f);
      data = pixels.data();
    }
    ok = out->write_image(OIIO::TypeDesc::FLOAT, data);
  } else {
    std::vector<unsigned char> px(image.rgb.size());
    for (size_t i = 0; i < px.size(); ++i) px[i] = encode_srgb8(image.rgb[i]);
    ok = out->write_image(OIIO::TypeDesc::UINT8, px.data());
  }
  std::string err = ok ? "" : out->geterror();
  ok = out->close() && ok;
  if (!ok) {
    std::remove(tmp.c_str());
    throw std::runtime_error("cannot write \"" + path + "\": " + err);
  }
  place_output(tmp, path);
}

Image read_image(const std::string& path) {
  auto in = OIIO::ImageInput::open(path);
  if (!in) throw std::runtime_error("cannot read \"" + path + "\": " + OIIO::geterror());
  const OIIO::ImageSpec& spec = in->spec();
  Image img;
  img.width = spec.width;
  img.height = spec.height;
  std::vector<float> data(size_t(spec.width) * size_t(spec.height) * size_t(spec.nchannels));
  if (!in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, data.data()))
    throw std::runtime_error("cannot decode \"" + path + "\": " + in->geterror());
  // Integer files hold encoded values: decoded by the rule textures follow
  // (texture/color_encoding.h), so an 8-bit PNG or JPEG, which renderers
  // write sRGB-encoded, compares with an EXR of the same render.
  const bool integer = spec.format.basetype == OIIO::TypeDesc::UINT8 || spec.format.basetype == OIIO::TypeDesc::UINT16;
  const ColorEncoding decoding = file_encoding(path, int(spec.format.size()) * 8, default_texture_encoding(path));
  // R, G, B by name where the file names them (OpenEXR keeps channels in
  // alphabetical order), else the first three; any others as extra
  // channels (a gbuffer's), in the file's order.
  int rgb[3] = {0, std::min(1, spec.nchannels - 1), std::min(2, spec.nchannels - 1)};
  const bool named = spec.channelindex("R") >= 0 && spec.channelindex("G") >= 0 && spec.channelindex("B") >= 0;
  if (named) rgb[0] = spec.channelindex("R"), rgb[1] = spec.channelindex("G"), rgb[2] = spec.channelindex("B");
  std::vector<int> extra;
  if (named)
    for (int k = 0; k < spec.nchannels; ++k)
      if (k != rgb[0] && k != rgb[1] && k != rgb[2] && spec.channelnames[size_t(k)] != "A") {
        extra.push_back(k);
        img.channel_names.push_back(spec.channelnames[size_t(k)]);
      }
  const size_t pixels = size_t(spec.width) * size_t(spec.height);
  img.rgb.resize(pixels * 3);
  img.channels.resize(pixels * extra.size());
  for (size_t i = 0; i < pixels; ++i) {
    for (int c = 0; c < 3; ++c) {
      const float v = data[i * size_t(spec.nchannels) + size_t(rgb[c])];
      img.rgb[3 * i + size_t(c)] = integer ? decoding.to_linear(v) : v;
    }
    for (size_t e = 0; e < extra.size(); ++e)
      img.channels[i * extra.size() + e] = data[i * size_t(spec.nchannels) + size_t(extra[e])];
  }
  return img;
}

ImageMetadata read_image_metadata(const std::string& path, const std::string& prefix) {
  auto in = OIIO::ImageInput::open(path);
  if (!in) throw std::runtime_error("cannot read \"" + path + "\": " + OIIO::geterror());
  ImageMetadata md;
  for (const OIIO::ParamValue& p : in->spec().extra_attribs) {
    std::string name = p.name().string();
    if (name.compare(0, prefix.size(), prefix) == 0 && p.type() == OIIO::TypeDesc::STRING)
      md.emplace_back(name, p.get_string());
  }
  return md;
}

TextureImage load_texture_image(const std::string& path, ColorEncoding encoding) {
  auto in = OIIO::ImageInput::open(path);
  if (!in) throw InputError({path, 0, 0}, "cannot read image: " + OIIO::geterror());
  const OIIO::ImageSpec& spec = in->spec();
  if (spec.width <= 0 || spec.height <= 0 || spec.nchannels <= 0 ||
      int64_t(spec.width) * spec.height > (int64_t(1) << 28))
    throw InputError({path, 0, 0},
                     "image has an unsupported size " + std::to_string(spec.width) + "x" + std::to_string(spec.height));
  int nc = spec.nchannels;
  std::vector<float> data(size_t(spec.width) * size_t(spec.height) * size_t(nc));
  if (!in->read_image(0, 0, 0, nc, OIIO::TypeDesc::FLOAT, data.data()))
    throw InputError({path, 0, 0}, "cannot decode image: " + in->geterror());
  const bool integer = spec.format.basetype == OIIO::TypeDesc::UINT8 || spec.format.basetype == OIIO::TypeDesc::UINT16;
  const ColorEncoding decoding = file_encoding(path, int(spec.format.size()) * 8, encoding);
  auto decode = [&](float v) { return integer ? decoding.to_linear(v) : v; };
  TextureImage img;
  img.filename = path;
  img.width = spec.width;
  img.height = spec.height;
  img.channels = nc >= 4 ? 4 : nc >= 3 ? 3 : 1;
  img.texels.resize(size_t(spec.width) * size_t(spec.height));
  if (img.channels == 4) img.alpha.resize(img.texels.size());
  double sum = 0.0;
  img.least = kInfinity;
  img.greatest = -kInfinity;
  for (size_t i = 0; i < img.texels.size(); ++i) {
    const float* px = &data[i * size_t(nc)];
    RGB c = nc >= 3 ? RGB(decode(px[0]), decode(px[1]), decode(px[2])) : RGB(decode(px[0]));
    if (!is_finite(c))
      throw InputError({path, 0, 0}, "image has a non-finite texel at (" + std::to_string(i % size_t(spec.width)) +
                                         ", " + std::to_string(i / size_t(spec.width)) + ")");
    img.texels[i] = max(c, RGB(0.f));
    sum += double(img.texels[i][0] + img.texels[i][1] + img.texels[i][2]) / 3.0;
    // pbrt-v4 decodes every channel of an integer file, alpha included.
    if (img.channels == 4) img.alpha[i] = glm::clamp(decode(px[3]), 0.f, 1.f);
    img.least = std::min({img.least, min_component(img.texels[i]), img.channels == 4 ? img.alpha[i] : kInfinity});
    img.greatest = std::max({img.greatest, max_component(img.texels[i]), img.channels == 4 ? img.alpha[i] : -kInfinity});
  }
  img.mean = float(sum / double(img.texels.size()));
  return img;
}

}  // namespace lantern::oiio
