// The image module's prepared textures (texture/prepared_texture.h).
#include "imageio/oiio_module.h"

#include <unistd.h>

#include <OpenImageIO/half.h>
#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>
#include <OpenImageIO/imageio.h>

#include <atomic>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <system_error>

#include "lantern/error.h"
#include "math/fnv1a.h"

namespace lantern::oiio {
namespace fs = std::filesystem;

namespace {

// Bumped when the prepared files' content changes, so stale ones are not reused.
constexpr char kFormatTag[] = "lantern-texture-2";

bool is_float_format(const OIIO::TypeDesc& t) {
  return t.basetype == OIIO::TypeDesc::FLOAT || t.basetype == OIIO::TypeDesc::HALF ||
         t.basetype == OIIO::TypeDesc::DOUBLE;
}

int texture_channels(int file_channels) { return file_channels >= 4 ? 4 : file_channels >= 3 ? 3 : 1; }

// A file the texture cache can read as it is: tiled, MIP-mapped, holding
// linear values (floats, or integers the scene declares linear).
bool usable_as_is(OIIO::ImageInput& in, ColorEncoding encoding) {
  const OIIO::ImageSpec spec = in.spec();
  if (spec.tile_width <= 0 || spec.depth > 1) return false;
  if (!is_float_format(spec.format) && encoding.kind != ColorEncoding::Linear) return false;
  return in.seek_subimage(0, 1);  // a second MIP level exists
}

// One prepared file per source path and encoding, so the directory does not
// grow as sources are edited: the file records which version of the source
// it was made from (source_stamp) and is remade when that changes.
std::string cache_name(const fs::path& source, ColorEncoding encoding) {
  std::error_code ec;
  fs::path abs = fs::absolute(source, ec);
  std::string key = std::string(kFormatTag) + "|" + (ec ? source.string() : abs.lexically_normal().string());
  Fnv1a h;
  h.add(key.data(), key.size());
  uint8_t kind = uint8_t(encoding.kind);
  h.add(&kind, 1);
  if (encoding.kind == ColorEncoding::Gamma) h.add(&encoding.gamma, sizeof encoding.gamma);
  char name[32];
  std::snprintf(name, sizeof name, "%016llx.exr", static_cast<unsigned long long>(h.h));
  return name;
}

std::string source_stamp(const fs::path& source) {
  std::error_code ec;
  uint64_t size = fs::file_size(source, ec);
  long long mtime = (long long)fs::last_write_time(source, ec).time_since_epoch().count();
  return std::to_string(size) + ":" + std::to_string(mtime);
}

constexpr char kStampAttribute[] = "lantern:source_stamp";
// The texels' bounds as written (PreparedTexture::least, greatest); files
// prepared before these were recorded have none, and read as unknown.
constexpr char kLeastAttribute[] = "lantern:least";
constexpr char kGreatestAttribute[] = "lantern:greatest";

// Whether target was made from this version of the source; if so, its
// recorded bounds go to out.
bool is_current(const fs::path& target, const std::string& stamp, PreparedTexture* out) {
  auto in = OIIO::ImageInput::open(target.string());
  if (!in || in->spec().get_string_attribute(kStampAttribute) != stamp) return false;
  const OIIO::ParamValue* lo = in->spec().find_attribute(kLeastAttribute, OIIO::TypeDesc::FLOAT);
  const OIIO::ParamValue* hi = in->spec().find_attribute(kGreatestAttribute, OIIO::TypeDesc::FLOAT);
  if (lo && hi) {
    out->least = lo->get_float();
    out->greatest = hi->get_float();
  }
  return true;
}

// A bound as the file stores it: rounding to half floats is monotonic, so
// the rounded bounds bound the rounded texels.
float as_stored(float v, bool to_half) { return to_half ? float(half(v)) : v; }

// Decodes the source (checking every texel) and writes it as a tiled,
// MIP-mapped OpenEXR file: half floats for decoded integer images, the
// source's own float type otherwise.
void convert(const std::string& source, ColorEncoding encoding, bool float_source, const fs::path& target,
             const std::string& stamp, PreparedTexture* out) {
  TextureImage img = oiio::load_texture_image(source, encoding);
  const int nc = img.channels;
  OIIO::ImageSpec spec(img.width, img.height, nc, OIIO::TypeDesc::FLOAT);
  spec.alpha_channel = -1;  // a value like the others: no premultiplication anywhere
  spec.attribute(kStampAttribute, stamp);
  if (img.least <= img.greatest) {
    out->least = as_stored(img.least, !float_source);
    out->greatest = as_stored(img.greatest, !float_source);
    spec.attribute(kLeastAttribute, out->least);
    spec.attribute(kGreatestAttribute, out->greatest);
  }
  OIIO::ImageBuf buf(spec);
  std::vector<float> row(size_t(img.width) * size_t(nc));
  for (int y = 0; y < img.height; ++y) {
    for (int x = 0; x < img.width; ++x) {
      size_t i = size_t(y) * size_t(img.width) + size_t(x);
      float* px = &row[size_t(x) * size_t(nc)];
      px[0] = img.texels[i][0];
      if (nc >= 3) px[1] = img.texels[i][1], px[2] = img.texels[i][2];
      if (nc == 4) px[3] = img.alpha[i];
    }
    buf.set_pixels(OIIO::ROI(0, img.width, y, y + 1, 0, 1, 0, nc), OIIO::TypeDesc::FLOAT, row.data());
  }
  img = TextureImage();  // the float copy in buf is all that is needed now

  OIIO::ImageSpec config;
  config.format = float_source ? OIIO::TypeDesc::FLOAT : OIIO::TypeDesc::HALF;
  config.tile_width = config.tile_height = 64;
  config.attribute("compression", "zip");
  config.attribute("maketx:compute_average", 0);
  config.attribute("maketx:fileformatname", "openexr");
  // A unique temporary name, renamed into place: another render preparing
  // the same texture at the same time never sees half a file.
  static std::atomic<unsigned> counter{0};
  fs::path tmp = target;
  tmp += ".tmp" + std::to_string(::getpid()) + "-" + std::to_string(counter++);
  if (!OIIO::ImageBufAlgo::make_texture(OIIO::ImageBufAlgo::MakeTxTexture, buf, tmp.string(), config)) {
    std::error_code ec;
    fs::remove(tmp, ec);
    throw InputError({source, 0, 0}, "cannot write its prepared texture " + tmp.string() + ": " + OIIO::geterror());
  }
  std::error_code ec;
  fs::rename(tmp, target, ec);
  if (ec) {
    fs::remove(tmp, ec);
    throw InputError({source, 0, 0}, "cannot write its prepared texture " + target.string() + ": " + ec.message());
  }
  out->converted = true;
}

}  // namespace

std::pair<int, int> image_resolution(const std::string& path) {
  auto in = OIIO::ImageInput::open(path);
  if (!in) throw InputError({path, 0, 0}, "cannot read image: " + OIIO::geterror());
  return {in->spec().width, in->spec().height};
}

PreparedTexture prepare_texture(const std::string& source, ColorEncoding encoding, const std::string& directory) {
  auto in = OIIO::ImageInput::open(source);
  if (!in) throw InputError({source, 0, 0}, "cannot read image: " + OIIO::geterror());
  const OIIO::ImageSpec spec = in->spec();
  if (spec.width <= 0 || spec.height <= 0 || spec.nchannels <= 0 || int64_t(spec.width) * spec.height > (int64_t(1) << 28))
    throw InputError({source, 0, 0}, "image has an unsupported size " + std::to_string(spec.width) + "x" +
                                         std::to_string(spec.height));
  PreparedTexture t;
  t.channels = texture_channels(spec.nchannels);
  t.width = spec.width;
  t.height = spec.height;
  const bool float_source = is_float_format(spec.format);
  // Prepared files are named by the encoding the source is decoded with, so
  // an 8-bit TGA asked for as linear shares the sRGB one (file_encoding).
  encoding = file_encoding(source, int(spec.format.size()) * 8, encoding);
  if (usable_as_is(*in, encoding)) {
    t.path = source;
    return t;
  }
  in.reset();
  std::error_code ec;
  fs::create_directories(directory, ec);
  if (ec)
    throw InputError({source, 0, 0}, "cannot create the texture directory " + directory + " (" + ec.message() +
                                         "); choose another with --texture-dir");
  fs::path target = fs::path(directory) / cache_name(source, encoding);
  t.path = target.string();
  const std::string stamp = source_stamp(source);
  if (fs::exists(target, ec) && is_current(target, stamp, &t)) return t;
  convert(source, encoding, float_source, target, stamp, &t);
  return t;
}

}  // namespace lantern::oiio
