// A scene with 200 distinct 2048x2048 image textures renders within the
// texture cache's limit plus a stated overhead, and its image does not
// depend on the cache size. The renders run as `lantern render` processes so
// that each one's peak resident memory is its own (wait4's ru_maxrss).
#include <gtest/gtest.h>

#include <OpenImageIO/half.h>
#include <OpenImageIO/imageio.h>
#include <spawn.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <thread>

#include "sanitizer.h"
#include "lantern/image.h"

extern char** environ;

namespace lantern {
namespace {

namespace fs = std::filesystem;

constexpr int kTextures = 200, kSize = 2048;

// Tiled, MIP-mapped, single-channel half-float OpenEXR files, as a texture
// pipeline would ship them: each distinct, each tile one value, so they
// compress to little on disk while the cache still holds full tiles.
void write_textures(const fs::path& dir) {
  auto write = [&](int first, int step) {
    std::vector<half> px(size_t(kSize) * kSize), values(200);
    for (int v = 0; v < 200; ++v) values[size_t(v)] = half(float(40 + v) / 255.f);
    for (int i = first; i < kTextures; i += step) {
      fs::path file = dir / ("t" + std::to_string(i) + ".exr");
      auto out = OIIO::ImageOutput::create(file.string());
      ASSERT_TRUE(out);
      OIIO::ImageSpec spec(kSize, kSize, 1, OIIO::TypeDesc::HALF);
      spec.tile_width = spec.tile_height = 64;
      spec.attribute("compression", "rle");  // fast, and tiny on one-value tiles
      spec.attribute("textureformat", "Plain Texture");  // a MIP-mapped file: the levels are appended below
      ASSERT_TRUE(out->open(file.string(), spec, OIIO::ImageOutput::Create)) << out->geterror();
      for (int level = 0, n = kSize; n >= 1; ++level, n /= 2) {
        if (level > 0) {
          spec.width = spec.height = spec.full_width = spec.full_height = n;
          ASSERT_TRUE(out->open(file.string(), spec, OIIO::ImageOutput::AppendMIPLevel)) << out->geterror();
        }
        // Texel (x, y) of level n lies in level-0 tile (x, y) * (kSize / n) / 64.
        const int scale = kSize / n;
        for (int y = 0; y < n; ++y) {
          half* row = &px[size_t(y) * size_t(n)];
          const int ty = y * scale / 64;
          if (y > 0 && (y - 1) * scale / 64 == ty) {  // (the rows of a tile are alike)
            std::copy(row - n, row, row);
            continue;
          }
          for (int x = 0; x < n; ++x) row[x] = values[size_t((i * 7 + x * scale / 64 * 3 + ty * 5) % 200)];
        }
        ASSERT_TRUE(out->write_image(OIIO::TypeDesc::HALF, px.data())) << out->geterror();
      }
      out->close();
    }
  };
  std::thread other(write, 1, 2);
  write(0, 2);
  other.join();
}

// A 20 x 10 wall of quads facing the camera, quad i textured by file i (or
// a constant, for the baseline).
std::string scene_text(const fs::path& dir, bool textured) {
  std::string s = R"(LookAt 10 5 -12  10 5 0  0 1 0
Camera "perspective" "float fov" 45
Film "rgb" "integer xresolution" 200 "integer yresolution" 100
Sampler "independent" "integer pixelsamples" 4
WorldBegin
LightSource "infinite" "rgb L" [1 1 1]
)";
  for (int i = 0; i < kTextures; ++i) {
    int x = i % 20, y = i / 20;
    std::string name = "t" + std::to_string(i);
    if (textured) {
      s += "Texture \"" + name + "\" \"spectrum\" \"imagemap\" \"string encoding\" \"linear\" \"string filename\" \"" +
           (dir / (name + ".exr")).string() + "\"\nMaterial \"diffuse\" \"texture reflectance\" \"" + name + "\"\n";
    } else {
      s += "Material \"diffuse\" \"rgb reflectance\" [0.5 0.5 0.5]\n";
    }
    s += "Shape \"bilinearmesh\" \"point3 P\" [" + std::to_string(x) + " " + std::to_string(y) + " 0 " +
         std::to_string(x + 1) + " " + std::to_string(y) + " 0 " + std::to_string(x) + " " + std::to_string(y + 1) +
         " 0 " + std::to_string(x + 1) + " " + std::to_string(y + 1) + " 0]\n";
  }
  return s;
}

// Runs lantern with args; returns its peak resident memory in MB.
double run_lantern(std::vector<std::string> args) {
  args.insert(args.begin(), LANTERN_BINARY);
  std::vector<char*> argv;
  for (auto& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  pid_t pid;
  EXPECT_EQ(posix_spawn(&pid, LANTERN_BINARY, nullptr, nullptr, argv.data(), environ), 0);
  int status = 0;
  struct rusage usage {};
  EXPECT_EQ(wait4(pid, &status, 0, &usage), pid);
  EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << "lantern failed: status " << status;
  return double(usage.ru_maxrss) / 1024.0;
}

TEST(TextureMemory, TwoHundredLargeTexturesRenderWithinTheCacheLimit) {
  if (LANTERN_ASAN) GTEST_SKIP() << "peak memory is the sanitizer's, not Lantern's";
  const fs::path dir = fs::temp_directory_path() / ("lantern-texture-memory-" + std::to_string(::getpid()));
  fs::create_directories(dir);
  auto t0 = std::chrono::steady_clock::now();
  write_textures(dir);
  std::printf("  writing: %.1f s\n", std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
  for (bool textured : {false, true}) {
    std::ofstream(dir / (textured ? "wall.pbrt" : "plain.pbrt")) << scene_text(dir, textured);
  }
  auto render = [&](const char* scene, const char* cache_mb, const char* out) {
    return run_lantern({"render", (dir / scene).string(), "--quiet", "--threads", "2", "--texture-cache", cache_mb,
                        "--texture-dir", (dir / "prepared").string(), "-o", (dir / out).string()});
  };
  const double plain = render("plain.pbrt", "32", "plain.exr");
  const double small = render("wall.pbrt", "32", "small.exr");
  const double large = render("wall.pbrt", "1024", "large.exr");
  std::printf("  peak RSS: constant textures %.0f MB, 32 MB cache %.0f MB, 1024 MB cache %.0f MB\n", plain, small,
              large);
  // The stated overhead past the limit: OpenImageIO's records of 200 files
  // and the buffers of up to 100 open ones, its per-thread tile caches, and
  // the allocator's slack (measured: about 32 MB; with a 1 MB cache the
  // render peaks 24-35 MB above the untextured one).
  const double overhead_mb = 64.0;
  EXPECT_LT(small - plain, 32.0 + overhead_mb);
  // The render touches far more texels than the small cache holds: with a
  // large cache they stay, which shows the limit is what bounds memory.
  EXPECT_GT(large - plain, 32.0 + overhead_mb + 64.0);
  EXPECT_FALSE(fs::exists(dir / "prepared")) << "tiled, MIP-mapped linear files are read where they are";
  Image a = read_image((dir / "small.exr").string()), b = read_image((dir / "large.exr").string());
  EXPECT_EQ(a.rgb, b.rgb) << "the image does not depend on the cache size";
  std::error_code ec;
  fs::remove_all(dir, ec);
}

}  // namespace
}  // namespace lantern
