// lantern-texbench: the cost of one image texture lookup, resident (a
// bilinear read of linear float texels held in memory) against OpenImageIO's
// TextureSystem (bilinear at full resolution, trilinear and anisotropic over
// a footprint), for incoherent (random) and coherent (a sweep) coordinates.
// The image is 1024x1024 RGB, written once to a temporary folder; the
// cache is big enough to hold it, so lookups measure filtering and the
// cache's tile search, not file reads.
#include <benchmark/benchmark.h>

#include <OpenImageIO/imageio.h>

#include <filesystem>
#include <memory>

#include "math/rng.h"
#include "texture/image.h"
#include "texture/texture_cache.h"

namespace {

using namespace lantern;

struct Fixture {
  std::string dir, source;
  TextureImage resident;
  std::unique_ptr<TextureCache> cache;
  int32_t bilinear = -1, trilinear = -1, ewa = -1;

  Fixture() {
    dir = (std::filesystem::temp_directory_path() / "lantern-texbench").string();
    std::filesystem::create_directories(dir);
    source = dir + "/source.exr";
    const int n = 1024;
    std::vector<float> px(size_t(n) * n * 3);
    for (int y = 0; y < n; ++y)
      for (int x = 0; x < n; ++x)
        for (int c = 0; c < 3; ++c) px[(size_t(y) * n + x) * 3 + c] = float((x * 7 + y * 13 + c * 5) % 256) / 255.f;
    auto out = OIIO::ImageOutput::create(source);
    out->open(source, OIIO::ImageSpec(n, n, 3, OIIO::TypeDesc::FLOAT));
    out->write_image(OIIO::TypeDesc::FLOAT, px.data());
    out->close();
    resident = load_texture_image(source, ColorEncoding{ColorEncoding::Linear});
    cache = std::make_unique<TextureCache>(TextureCacheSettings{256.0, dir + "/prepared"});
    PreparedTexture t = prepare_texture(source, ColorEncoding{ColorEncoding::Linear}, dir + "/prepared");
    bilinear = cache->add(t, ImageFilter::Bilinear, WrapMode::Repeat, 8.f);
    trilinear = cache->add(t, ImageFilter::Trilinear, WrapMode::Repeat, 8.f);
    ewa = cache->add(t, ImageFilter::EWA, WrapMode::Repeat, 8.f);
  }
};

Fixture& fixture() {
  static Fixture f;
  return f;
}

// Coordinates: random over the image, or a sweep one texel apart.
Vec2 coordinate(bool coherent, uint64_t i, RandomStream& s) {
  if (!coherent) return Vec2(s.get1d(), s.get1d());
  return Vec2(float(i % 1024) / 1024.f + 0.0005f, float((i / 1024) % 1024) / 1024.f + 0.0005f);
}

void Resident(benchmark::State& state) {
  Fixture& f = fixture();
  RandomStream s = RandomStream::make(1, 2, 3);
  uint64_t i = 0;
  for (auto _ : state) {
    RGB v = f.resident.lookup_rgb(coordinate(state.range(0), i++, s), ImageFilter::Bilinear, WrapMode::Repeat);
    benchmark::DoNotOptimize(v);
  }
}

void Cached(benchmark::State& state, int filter) {
  Fixture& f = fixture();
  const int32_t id = filter == 0 ? f.bilinear : filter == 1 ? f.trilinear : f.ewa;
  RandomStream s = RandomStream::make(1, 2, 3);
  uint64_t i = 0;
  // A footprint of about 4 texels across, stretched 4:1 for the anisotropic filter.
  const Vec2 dx(4.f / 1024.f, 0.f), dy(0.f, filter == 2 ? 1.f / 1024.f : 4.f / 1024.f);
  for (auto _ : state) {
    TextureLookup q{coordinate(state.range(0), i++, s), dx, dy};
    RGB v = f.cache->lookup_rgb(id, q);
    benchmark::DoNotOptimize(v);
  }
}

BENCHMARK(Resident)->ArgName("coherent")->Arg(0)->Arg(1);
BENCHMARK_CAPTURE(Cached, bilinear, 0)->ArgName("coherent")->Arg(0)->Arg(1);
BENCHMARK_CAPTURE(Cached, trilinear, 1)->ArgName("coherent")->Arg(0)->Arg(1);
BENCHMARK_CAPTURE(Cached, ewa, 2)->ArgName("coherent")->Arg(0)->Arg(1);

}  // namespace

BENCHMARK_MAIN();
