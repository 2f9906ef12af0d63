// How each image format's values are decoded, as pbrt-v4 decodes them:
// every 8-bit format but PNG is sRGB whatever the scene's `encoding` says
// (pbrt-v4 reads them through stb_image and marks them sRGB), PNG follows
// `encoding` at 8 and 16 bits, float formats are linear. One file of a
// mid-grey per format and bit depth, read resident, through the prepared
// texture files the cache reads, and through a scene's imagemap and normal
// map. docs/textures.md has the same table.
#include <gtest/gtest.h>

#include <OpenImageIO/imagebuf.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <filesystem>

#include "lantern/image.h"
#include "lantern/scene.h"
#include "scene/scene.h"
#include "texture/image.h"
#include "texture/prepared_texture.h"
#include "texture/texture.h"
#include "texture/texture_cache.h"

namespace lantern {
namespace {

namespace fs = std::filesystem;

fs::path formats_dir() {
  fs::path dir = fs::temp_directory_path() / ("lantern-format-test-" + std::to_string(::getpid()));
  fs::create_directories(dir);
  return dir;
}

float srgb_decoded(float v) { return v <= 0.04045f ? v / 12.92f : std::pow((v + 0.055f) / 1.055f, 2.4f); }

// A 4x4 RGB file whose every value is `stored` (0..1) in `type`; returns its path.
std::string write_grey(const std::string& name, OIIO::TypeDesc type, float stored) {
  std::string path = (formats_dir() / name).string();
  if (lowercase_extension(path) == "pfm") {  // OpenImageIO here reads PFM but does not write it
    std::FILE* f = std::fopen(path.c_str(), "wb");
    std::fputs("PF\n4 4\n-1.0\n", f);  // colour, 4x4, little-endian
    for (int i = 0; i < 4 * 4 * 3; ++i) std::fwrite(&stored, sizeof stored, 1, f);
    std::fclose(f);
    return path;
  }
  OIIO::ImageBuf buf(OIIO::ImageSpec(4, 4, 3, type));
  const float px[3] = {stored, stored, stored};
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < 4; ++x) buf.setpixel(x, y, 0, px, 3);
  EXPECT_TRUE(buf.write(path, type)) << name << ": " << buf.geterror();
  return path;
}

enum class Expect { SRGB, Requested, Stored };

struct ImageFormat {
  const char* name;
  OIIO::TypeDesc type;
  Expect rule;
};

// The table of docs/textures.md. 8-bit files store 128/255; 16-bit files
// 32896/65535 (the same value); float files the value itself.
const ImageFormat kImageFormats[] = {
    {"grey8.png", OIIO::TypeDesc::UINT8, Expect::Requested},
    {"grey16.png", OIIO::TypeDesc::UINT16, Expect::Requested},
    {"grey8.tga", OIIO::TypeDesc::UINT8, Expect::SRGB},
    {"grey8.TGA", OIIO::TypeDesc::UINT8, Expect::SRGB},  // extensions in any case
    {"grey8.jpg", OIIO::TypeDesc::UINT8, Expect::SRGB},
    {"grey8.jpeg", OIIO::TypeDesc::UINT8, Expect::SRGB},
    {"grey8.bmp", OIIO::TypeDesc::UINT8, Expect::SRGB},
    {"grey8.gif", OIIO::TypeDesc::UINT8, Expect::SRGB},
    {"grey8.ppm", OIIO::TypeDesc::UINT8, Expect::SRGB},
    {"grey16.ppm", OIIO::TypeDesc::UINT16, Expect::SRGB},  // pbrt-v4 reduces it to 8 bits, still sRGB
    {"grey8.tif", OIIO::TypeDesc::UINT8, Expect::SRGB},
    {"grey16.tif", OIIO::TypeDesc::UINT16, Expect::Requested},
    {"grey.exr", OIIO::TypeDesc::HALF, Expect::Stored},
    {"grey.hdr", OIIO::TypeDesc::FLOAT, Expect::Stored},
    {"grey.pfm", OIIO::TypeDesc::FLOAT, Expect::Stored},
};

float stored_value(const ImageFormat& f) {
  if (f.type == OIIO::TypeDesc::UINT8) return 128.f / 255.f;
  if (f.type == OIIO::TypeDesc::UINT16) return 32896.f / 65535.f;
  return 0.375f;
}

float expected(const ImageFormat& f, ColorEncoding requested) {
  const float v = stored_value(f);
  switch (f.rule) {
    case Expect::SRGB: return srgb_decoded(v);
    case Expect::Requested: return requested.to_linear(v);
    case Expect::Stored: break;
  }
  return v;
}

const ColorEncoding kRequests[] = {ColorEncoding{ColorEncoding::SRGB}, ColorEncoding{ColorEncoding::Linear},
                                   ColorEncoding{ColorEncoding::Gamma, 2.2f}};

TEST(ImageFormats, ResidentImagesDecodeAsPbrtV4Does) {
  for (const ImageFormat& f : kImageFormats) {
    const std::string path = write_grey(f.name, f.type, stored_value(f));
    for (ColorEncoding e : kRequests) {
      TextureImage img = load_texture_image(path, e);
      const float want = expected(f, e);
      // JPEG and HDR store a uniform grey to within one step of their code.
      EXPECT_NEAR(img.texels[5][0], want, want * 0.01f) << f.name << " asked as kind " << int(e.kind);
      EXPECT_FLOAT_EQ(img.texels[5][0], img.texels[5][2]) << f.name;
    }
  }
}

TEST(ImageFormats, PreparedTexturesDecodeAsResidentOnes) {
  const fs::path dir = formats_dir() / "prepared";
  TextureCache cache(TextureCacheSettings{64, dir.string()});
  for (const ImageFormat& f : kImageFormats) {
    const std::string path = write_grey(f.name, f.type, stored_value(f));
    for (ColorEncoding e : kRequests) {
      PreparedTexture t = prepare_texture(path, e, dir.string());
      const int32_t h = cache.add(t, ImageFilter::Bilinear, WrapMode::Clamp, 8.f);
      const float want = expected(f, e);
      // Prepared files hold half floats: 11 significant bits.
      EXPECT_NEAR(cache.lookup_rgb(h, TextureLookup{Vec2(0.5f)})[0], want, want * 0.01f)
          << f.name << " asked as kind " << int(e.kind);
    }
  }
}

// Through the scene language, as a scene gives it: an imagemap with and
// without "encoding", read resident (bilinear) and through the cache
// (trilinear).
TEST(ImageFormats, SceneImageTexturesFollowTheRule) {
  for (const char* name : {"grey8.tga", "grey8.jpg", "grey8.png", "grey16.png"}) {
    const ImageFormat* f = nullptr;
    for (const ImageFormat& k : kImageFormats) f = std::string(k.name) == name ? &k : f;
    const std::string path = write_grey(name, f->type, stored_value(*f));
    struct Case {
      const char* param;
      ColorEncoding asked;
    } cases[] = {{"", default_texture_encoding(path)},
                 {"\"string encoding\" \"linear\"", ColorEncoding{ColorEncoding::Linear}},
                 {"\"string encoding\" \"sRGB\"", ColorEncoding{ColorEncoding::SRGB}}};
    for (const Case& c : cases)
      for (const char* filter : {"bilinear", "trilinear"}) {
        LoadOptions opts;
        opts.texture_directory = (formats_dir() / "scene").string();
        auto s = load_scene_from_string(std::string("WorldBegin\nTexture \"t\" \"spectrum\" \"imagemap\" \"string filename\" \"") +
                                            path + "\" \"string filter\" \"" + filter + "\" " + c.param +
                                            "\nMaterial \"diffuse\" \"texture reflectance\" \"t\"\nShape \"sphere\"\n",
                                        "t.pbrt", opts);
        const RGBTextureRef& t = s->materials.diffuse.at(0).reflectance;
        const float got = s->textures.evaluate(t, TextureContext{Vec3(0.f), Vec3(0, 0, 1), Vec2(0.5f)})[0];
        const float want = expected(*f, c.asked);
        EXPECT_NEAR(got, want, want * 0.01f) << name << " " << c.param << " " << filter;
      }
  }
}

// Film "savefp16" (pbrt-v4's parameter): 16-bit floats in an OpenEXR
// output, a value above half's largest kept at it rather than made
// infinite; 32-bit floats without it, and 8-bit formats unchanged.
TEST(ImageFormats, SaveFp16WritesHalfFloatExr) {
  EXPECT_TRUE(load_scene_from_string("Film \"rgb\" \"bool savefp16\" true\nWorldBegin\n", "f.pbrt", {})->settings.save_fp16);
  EXPECT_FALSE(load_scene_from_string("Film \"rgb\"\nWorldBegin\n", "f.pbrt", {})->settings.save_fp16);
  Image img;
  img.width = 2;
  img.height = 1;
  img.rgb = {1.f, 0.1f, 1e6f, 0.25f, 70000.f, -1e6f};
  for (const bool half : {true, false}) {
    const std::string path = (formats_dir() / (half ? "half.exr" : "float.exr")).string();
    write_image(path, img, half ? ImageMetadata{{"half", "true"}} : ImageMetadata{});
    auto in = OIIO::ImageInput::open(path);
    ASSERT_TRUE(in) << path;
    EXPECT_EQ(in->spec().format, half ? OIIO::TypeDesc::HALF : OIIO::TypeDesc::FLOAT) << path;
    std::vector<float> px(6);
    ASSERT_TRUE(in->read_image(0, 0, 0, 3, OIIO::TypeDesc::FLOAT, px.data()));
    const std::vector<float> want = half ? std::vector<float>{1.f, 0.1f, 65504.f, 0.25f, 65504.f, -65504.f} : img.rgb;
    for (size_t i = 0; i < px.size(); ++i) EXPECT_NEAR(px[i], want[i], std::fabs(want[i]) * 1e-3f) << path << " value " << i;
  }
  // An 8-bit output ignores it.
  const std::string png = (formats_dir() / "half.png").string();
  write_image(png, img, ImageMetadata{{"half", "true"}});
  EXPECT_EQ(OIIO::ImageInput::open(png)->spec().format, OIIO::TypeDesc::UINT8);
}

}  // namespace
}  // namespace lantern
