// Image textures through the texture cache: prepared files made once and
// remade when their source changes, the cache's lookups against the
// resident image's (pbrt-v4's bilinear and point filters, wrap modes,
// float semantics), MIP filtering over a footprint, and clear errors.
#include <gtest/gtest.h>

#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>
#include <unistd.h>

#include <filesystem>
#include <thread>

#include "lantern/error.h"
#include "lantern/image.h"
#include "lantern/render.h"
#include "lantern/scene.h"
#include "math/rng.h"
#include "scene/scene.h"
#include "texture/texture_cache.h"

namespace lantern {
namespace {

namespace fs = std::filesystem;

fs::path test_dir() {
  fs::path dir = fs::temp_directory_path() / ("lantern-cache-test-" + std::to_string(::getpid()));
  fs::create_directories(dir);
  return dir;
}

// A w x h image of nc channels with values from f(x, y, c), written as a
// linear float file.
template <class F>
std::string write_float_image(const std::string& name, int w, int h, int nc, F&& f) {
  std::string path = (test_dir() / name).string();
  OIIO::ImageBuf buf(OIIO::ImageSpec(w, h, nc, OIIO::TypeDesc::FLOAT));
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      std::vector<float> px(static_cast<size_t>(nc));
      for (int c = 0; c < nc; ++c) px[size_t(c)] = f(x, y, c);
      buf.setpixel(x, y, 0, px.data(), nc);
    }
  EXPECT_TRUE(buf.write(path)) << buf.geterror();
  return path;
}

TEST(TextureCache, PreparedOnceAndRemadeWhenTheSourceChanges) {
  const fs::path dir = test_dir() / "prepared-once";
  std::string src = write_float_image("change.exr", 8, 8, 3, [](int, int, int) { return 0.25f; });
  PreparedTexture a = prepare_texture(src, ColorEncoding{ColorEncoding::Linear}, dir.string());
  EXPECT_TRUE(a.converted) << "an untiled file is prepared";
  EXPECT_EQ(a.channels, 3);
  PreparedTexture b = prepare_texture(src, ColorEncoding{ColorEncoding::Linear}, dir.string());
  EXPECT_FALSE(b.converted) << "and reused";
  EXPECT_EQ(a.path, b.path);
  // Another encoding is another prepared file.
  PreparedTexture c = prepare_texture(src, ColorEncoding{ColorEncoding::SRGB}, dir.string());
  EXPECT_NE(c.path, a.path);
  // Edit the source (a later modification time): the same prepared file is remade.
  std::this_thread::sleep_for(std::chrono::milliseconds(20));
  write_float_image("change.exr", 8, 8, 3, [](int, int, int) { return 0.75f; });
  PreparedTexture d = prepare_texture(src, ColorEncoding{ColorEncoding::Linear}, dir.string());
  EXPECT_TRUE(d.converted);
  EXPECT_EQ(d.path, a.path);
  TextureCache cache(TextureCacheSettings{16.0, dir.string()});
  int32_t id = cache.add(d, ImageFilter::Bilinear, WrapMode::Repeat, 8.f);
  EXPECT_FLOAT_EQ(cache.lookup_rgb(id, TextureLookup{Vec2(0.5f)})[0], 0.75f);
  EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator()), 2) << "one file per source and encoding";
}

TEST(TextureCache, TiledMipMappedLinearFilesAreReadWhereTheyAre) {
  std::string src = write_float_image("flat.exr", 16, 16, 1, [](int x, int, int) { return float(x) / 16.f; });
  std::string tx = (test_dir() / "made.exr").string();
  OIIO::ImageBuf in(src);
  OIIO::ImageSpec config;
  config.tile_width = config.tile_height = 8;
  ASSERT_TRUE(OIIO::ImageBufAlgo::make_texture(OIIO::ImageBufAlgo::MakeTxTexture, in, tx, config));
  PreparedTexture t = prepare_texture(tx, ColorEncoding{ColorEncoding::Linear}, (test_dir() / "unused").string());
  EXPECT_FALSE(t.converted);
  EXPECT_EQ(t.path, tx);
  EXPECT_FALSE(fs::exists(test_dir() / "unused"));
}

// The cache's point and bilinear lookups equal the resident image's (within
// the half floats prepared files hold) for every wrap mode, in RGB and in
// each float reading: a grey file's value, RGB's mean, RGBA's alpha.
TEST(TextureCache, LookupsMatchTheResidentImage) {
  const fs::path dir = test_dir() / "match";
  auto value = [](int x, int y, int c) { return float((x * 37 + y * 11 + c * 71) % 97) / 96.f; };
  for (int nc : {1, 3, 4}) {
    std::string src = write_float_image("m" + std::to_string(nc) + ".exr", 13, 7, nc, value);
    TextureImage resident = load_texture_image(src, ColorEncoding{ColorEncoding::Linear});
    PreparedTexture prepared = prepare_texture(src, ColorEncoding{ColorEncoding::Linear}, dir.string());
    TextureCache cache(TextureCacheSettings{16.0, dir.string()});
    RandomStream s = RandomStream::make(7, uint64_t(nc), 0);
    for (ImageFilter filter : {ImageFilter::Point, ImageFilter::Bilinear})
      for (WrapMode wrap : {WrapMode::Repeat, WrapMode::Clamp, WrapMode::Black}) {
        int32_t id = cache.add(prepared, filter, wrap, 8.f);
        for (int i = 0; i < 400; ++i) {
          Vec2 st(3.f * s.get1d() - 1.f, 3.f * s.get1d() - 1.f);
          RGB want = resident.lookup_rgb(st, filter, wrap), got = cache.lookup_rgb(id, TextureLookup{st});
          for (int c = 0; c < 3; ++c)
            ASSERT_NEAR(got[c], want[c], 1e-3f) << nc << " channels, filter " << int(filter) << " wrap " << int(wrap)
                                                << " at " << st.x << ", " << st.y;
          ASSERT_NEAR(cache.lookup_float(id, TextureLookup{st}), resident.lookup_float(st, filter, wrap), 1e-3f)
              << nc << " channels, float, filter " << int(filter) << " wrap " << int(wrap);
        }
      }
  }
}

// A checker of single texels: unfiltered lookups see 0 or 1; a trilinear
// or anisotropic lookup over a footprint of many texels sees the mean.
TEST(TextureCache, MipFiltersAverageOverTheFootprint) {
  const fs::path dir = test_dir() / "mip";
  std::string src = write_float_image("fine.exr", 256, 256, 1, [](int x, int y, int) { return float((x + y) & 1); });
  PreparedTexture prepared = prepare_texture(src, ColorEncoding{ColorEncoding::Linear}, dir.string());
  TextureCache cache(TextureCacheSettings{16.0, dir.string()});
  const int32_t bilinear = cache.add(prepared, ImageFilter::Bilinear, WrapMode::Repeat, 8.f);
  const int32_t trilinear = cache.add(prepared, ImageFilter::Trilinear, WrapMode::Repeat, 8.f);
  const int32_t ewa = cache.add(prepared, ImageFilter::EWA, WrapMode::Repeat, 8.f);
  const Vec2 texel_centre((10.f + 0.5f) / 256.f, (20.f + 0.5f) / 256.f);  // x + y even: 0
  const Vec2 wide(32.f / 256.f, 0.f), tall(0.f, 32.f / 256.f), thin(0.f, 8.f / 256.f);
  EXPECT_NEAR(cache.lookup_float(bilinear, TextureLookup{texel_centre, wide, tall}), 0.f, 1e-6f) << "no MIP";
  EXPECT_NEAR(cache.lookup_float(trilinear, TextureLookup{texel_centre}), 0.f, 1e-6f) << "zero footprint";
  EXPECT_NEAR(cache.lookup_float(trilinear, TextureLookup{texel_centre, wide, tall}), 0.5f, 0.01f);
  EXPECT_NEAR(cache.lookup_float(ewa, TextureLookup{texel_centre, wide, thin}), 0.5f, 0.01f) << "4:1 footprint";
}

TEST(TextureCache, AnUnwritableTextureDirectoryIsAClearError) {
  std::string src = write_float_image("small.exr", 2, 2, 3, [](int, int, int) { return 0.5f; });
  // A folder cannot be made inside a regular file.
  std::string blocker = (test_dir() / "a-file").string();
  { std::FILE* f = std::fopen(blocker.c_str(), "w"); std::fclose(f); }
  try {
    prepare_texture(src, ColorEncoding{ColorEncoding::Linear}, blocker + "/textures");
    ADD_FAILURE() << "no error";
  } catch (const InputError& e) {
    std::string msg = e.what();
    EXPECT_NE(msg.find("small.exr"), std::string::npos) << msg;
    EXPECT_NE(msg.find("--texture-dir"), std::string::npos) << msg;
  }
}

}  // namespace
}  // namespace lantern

namespace lantern {
namespace {

// --stats counts the cache's lookups and, timed, the thread-seconds in them.
TEST(TextureCache, RenderStatsCountLookups) {
  std::string src = write_float_image("stats.exr", 300, 300, 3, [](int x, int y, int c) {
    return float((x + y + c) % 7) / 7.f;
  });
  auto scene = load_scene_from_string(R"(LookAt 0 0 -3  0 0 0  0 1 0
Camera "perspective" "float fov" 40
WorldBegin
LightSource "infinite" "rgb L" [1 1 1]
Texture "t" "spectrum" "imagemap" "string filename" ")" + src + R"("
Material "diffuse" "texture reflectance" "t"
Shape "bilinearmesh" "point3 P" [-1 -1 0  1 -1 0  -1 1 0  1 1 0]
)",
                                      "stats.pbrt", {});
  ASSERT_TRUE(scene->textures.cache) << "300x300 is past the resident size";
  RenderOptions o;
  o.spp = 1;
  o.width = 16;
  o.height = 16;
  o.collect_stats = true;
  RenderResult r = render(*scene, o);
  EXPECT_TRUE(r.stats.texture_cache);
  EXPECT_GE(r.stats.texture_lookups, 16 * 16 / 2) << "the quad fills most of the image";
  EXPECT_GT(r.stats.texture_lookup_seconds, 0.0);
  EXPECT_GT(r.stats.texture_tiles_read, 0);
  EXPECT_EQ(r.stats.texture_failed_lookups, 0);
  o.collect_stats = false;
  RenderResult untimed = render(*scene, o);
  EXPECT_EQ(untimed.stats.texture_lookups, r.stats.texture_lookups) << "counted afresh for each render";
  EXPECT_EQ(untimed.stats.texture_lookup_seconds, 0.0);
}

}  // namespace
}  // namespace lantern
