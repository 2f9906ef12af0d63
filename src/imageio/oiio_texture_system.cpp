// The image module's texture cache: one OpenImageIO TextureSystem with its
// own ImageCache (its memory limit is the scene's), and per registered
// texture the lookup options, built once.
#include "imageio/oiio_module.h"

#include <OpenImageIO/texture.h>

#include <tbb/enumerable_thread_specific.h>

#include <atomic>
#include <chrono>
#include <vector>

#include "lantern/error.h"

namespace lantern::oiio {
namespace {

struct Cache {
  struct Entry {
    OIIO::TextureSystem::TextureHandle* handle = nullptr;
    OIIO::TextureOpt opt;
  };
  struct Counts {
    int64_t lookups = 0;
    double seconds = 0.0;
  };
  OIIO::TextureSystem* ts = nullptr;
  std::vector<Entry> entries;
  std::atomic<int64_t> failed{0};
  tbb::enumerable_thread_specific<Counts> counts;  // per thread: no shared counter on the hot path
  bool timed = false;
};

OIIO::TextureOpt::Wrap oiio_wrap(WrapMode w) {
  switch (w) {
    case WrapMode::Black: return OIIO::TextureOpt::WrapBlack;
    case WrapMode::Clamp: return OIIO::TextureOpt::WrapClamp;
    case WrapMode::Repeat:
    case WrapMode::OctahedralSphere: break;  // not offered by OpenImageIO; such images stay resident
  }
  return OIIO::TextureOpt::WrapPeriodic;
}

}  // namespace

void* cache_create(double max_memory_mb) {
  auto* c = new Cache;
  // A cache of its own, not the process-wide shared one: its limit is this scene's.
  c->ts = OIIO::TextureSystem::create(false);
  c->ts->attribute("max_memory_MB", float(max_memory_mb));
  // OpenImageIO's default: each open file holds buffers outside the tile
  // limit, so this bounds that overhead too.
  c->ts->attribute("max_open_files", 100);
  c->ts->attribute("automip", 0);
  c->ts->attribute("autotile", 0);
  return c;
}

void cache_destroy(void* cache) {
  auto* c = static_cast<Cache*>(cache);
  OIIO::TextureSystem::destroy(c->ts);
  delete c;
}

int32_t cache_add(void* cache, const std::string& path, ImageFilter filter, WrapMode wrap, float max_anisotropy) {
  auto* c = static_cast<Cache*>(cache);
  Cache::Entry e;
  e.handle = c->ts->get_texture_handle(OIIO::ustring(path));
  if (!e.handle || !c->ts->good(e.handle))
    throw InputError({path, 0, 0}, "the texture cache cannot open it: " + c->ts->geterror());
  OIIO::TextureOpt& o = e.opt;
  o.swrap = o.twrap = oiio_wrap(wrap);
  o.fill = 0.f;
  switch (filter) {
    case ImageFilter::Point:
      o.interpmode = OIIO::TextureOpt::InterpClosest;
      o.mipmode = OIIO::TextureOpt::MipModeNoMIP;
      break;
    case ImageFilter::Bilinear:
      o.interpmode = OIIO::TextureOpt::InterpBilinear;
      o.mipmode = OIIO::TextureOpt::MipModeNoMIP;
      break;
    case ImageFilter::Trilinear:
      o.interpmode = OIIO::TextureOpt::InterpBilinear;
      o.mipmode = OIIO::TextureOpt::MipModeTrilinear;
      break;
    case ImageFilter::EWA:
      o.interpmode = OIIO::TextureOpt::InterpBilinear;
      o.mipmode = OIIO::TextureOpt::MipModeAniso;
      o.anisotropic = std::max(1, int(std::lround(max_anisotropy)));
      break;
  }
  c->entries.push_back(e);
  return int32_t(c->entries.size() - 1);
}

bool cache_texture(void* cache, int32_t id, const TextureLookup& q, int first, int n, float* out) {
  auto* c = static_cast<Cache*>(cache);
  const Cache::Entry& e = c->entries[size_t(id)];
  OIIO::TextureOpt opt = e.opt;  // OpenImageIO takes it by non-const reference
  opt.firstchannel = first;
  Cache::Counts& k = c->counts.local();
  ++k.lookups;
  using Clock = std::chrono::steady_clock;
  const Clock::time_point t0 = c->timed ? Clock::now() : Clock::time_point();
  bool ok = c->ts->texture(e.handle, c->ts->get_perthread_info(), opt, q.st.x, q.st.y, q.dst_dx.x, q.dst_dx.y,
                           q.dst_dy.x, q.dst_dy.y, n, out);
  if (c->timed) k.seconds += std::chrono::duration<double>(Clock::now() - t0).count();
  if (!ok) c->failed.fetch_add(1, std::memory_order_relaxed);
  return ok;
}

TextureCacheStats cache_stats(void* cache) {
  auto* c = static_cast<Cache*>(cache);
  TextureCacheStats s;
  int tiles = 0, peak = 0;
  long long bytes = 0, memory = 0;
  c->ts->getattribute("stat:bytes_read", OIIO::TypeDesc::INT64, &bytes);
  c->ts->getattribute("stat:cache_memory_used", OIIO::TypeDesc::INT64, &memory);
  c->ts->getattribute("stat:tiles_created", tiles);
  c->ts->getattribute("stat:tiles_peak", peak);
  s.bytes_read = bytes;
  s.memory_bytes = memory;
  s.tiles_read = tiles;
  s.peak_tiles = peak;
  s.failed_lookups = c->failed.load();
  for (const Cache::Counts& k : c->counts) {
    s.lookups += k.lookups;
    s.lookup_seconds += k.seconds;
  }
  return s;
}

void cache_reset_lookup_stats(void* cache, bool timed) {
  auto* c = static_cast<Cache*>(cache);
  c->counts.clear();
  c->timed = timed;
}

}  // namespace lantern::oiio
