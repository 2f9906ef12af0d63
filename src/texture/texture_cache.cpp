#include "texture/texture_cache.h"

#include <OpenImageIO/texture.h>

#include <tbb/enumerable_thread_specific.h>

#include <atomic>
#include <chrono>
#include <vector>

#include "lantern/error.h"

namespace lantern {

struct TextureCache::Impl {
  struct Entry {
    OIIO::TextureSystem::TextureHandle* handle = nullptr;
    OIIO::TextureOpt opt;
    int channels = 3;
    bool point = false;
  };
  struct Counts {
    int64_t lookups = 0;
    double seconds = 0.0;
  };
  OIIO::TextureSystem* ts = nullptr;
  std::vector<Entry> entries;
  mutable std::atomic<int64_t> failed{0};
  mutable tbb::enumerable_thread_specific<Counts> counts;  // per thread: no shared counter on the hot path
  bool timed = false;

  // One lookup of n channels from `first`; false if the file failed.
  bool texture(const Entry& e, const TextureLookup& q, int first, int n, float* out) const {
    OIIO::TextureOpt opt = e.opt;  // OpenImageIO takes it by non-const reference
    opt.firstchannel = first;
    Counts& c = counts.local();
    ++c.lookups;
    using Clock = std::chrono::steady_clock;
    const Clock::time_point t0 = timed ? Clock::now() : Clock::time_point();
    bool ok = ts->texture(e.handle, ts->get_perthread_info(), opt, q.st.x, q.st.y, q.dst_dx.x, q.dst_dx.y, q.dst_dy.x,
                          q.dst_dy.y, n, out);
    if (timed) c.seconds += std::chrono::duration<double>(Clock::now() - t0).count();
    if (!ok) {
      failed.fetch_add(1, std::memory_order_relaxed);
      for (int i = 0; i < n; ++i) out[i] = 0.f;
    }
    return ok;
  }
};

namespace {

OIIO::TextureOpt::Wrap oiio_wrap(WrapMode w) {
  switch (w) {
    case WrapMode::Black: return OIIO::TextureOpt::WrapBlack;
    case WrapMode::Clamp: return OIIO::TextureOpt::WrapClamp;
    case WrapMode::Repeat:
    case WrapMode::OctahedralSphere: break;  // not offered by OpenImageIO; such images stay resident
  }
  return OIIO::TextureOpt::WrapPeriodic;
}

float sanitized(float v) { return std::isfinite(v) && v > 0.f ? v : 0.f; }

}  // namespace

TextureCache::TextureCache(const TextureCacheSettings& settings) : settings_(settings), impl_(new Impl) {
  if (settings_.directory.empty()) settings_.directory = default_texture_directory();
  // A cache of its own, not the process-wide shared one: its limit is this scene's.
  impl_->ts = OIIO::TextureSystem::create(false);
  impl_->ts->attribute("max_memory_MB", float(settings_.max_memory_mb));
  // OpenImageIO's default: each open file holds buffers outside the tile
  // limit, so this bounds that overhead too.
  impl_->ts->attribute("max_open_files", 100);
  impl_->ts->attribute("automip", 0);
  impl_->ts->attribute("autotile", 0);
}

TextureCache::~TextureCache() { OIIO::TextureSystem::destroy(impl_->ts); }

int32_t TextureCache::add(const PreparedTexture& t, ImageFilter filter, WrapMode wrap, float max_anisotropy) {
  Impl::Entry e;
  e.handle = impl_->ts->get_texture_handle(OIIO::ustring(t.path));
  if (!e.handle || !impl_->ts->good(e.handle))
    throw InputError({t.path, 0, 0}, "the texture cache cannot open it: " + impl_->ts->geterror());
  e.channels = t.channels;
  e.point = filter == ImageFilter::Point;
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
  impl_->entries.push_back(e);
  return int32_t(impl_->entries.size() - 1);
}

RGB TextureCache::lookup_rgb(int32_t id, const TextureLookup& q) const {
  const Impl::Entry& e = impl_->entries[size_t(id)];
  float v[3] = {0.f, 0.f, 0.f};
  if (e.channels == 1) {
    impl_->texture(e, q, 0, 1, v);
    return RGB(sanitized(v[0]));
  }
  impl_->texture(e, q, 0, 3, v);
  return RGB(sanitized(v[0]), sanitized(v[1]), sanitized(v[2]));
}

float TextureCache::lookup_float(int32_t id, const TextureLookup& q) const {
  const Impl::Entry& e = impl_->entries[size_t(id)];
  float v[3] = {0.f, 0.f, 0.f};
  if (e.point || e.channels == 1) {
    impl_->texture(e, q, 0, 1, v);
    return sanitized(v[0]);
  }
  if (e.channels == 4) {
    impl_->texture(e, q, 3, 1, v);
    return std::fmin(sanitized(v[0]), 1.f);
  }
  impl_->texture(e, q, 0, 3, v);
  return (sanitized(v[0]) + sanitized(v[1]) + sanitized(v[2])) / 3.f;
}

TextureCacheStats TextureCache::stats() const {
  TextureCacheStats s;
  OIIO::TextureSystem* ts = impl_->ts;
  int tiles = 0, peak = 0;
  long long bytes = 0, memory = 0;
  ts->getattribute("stat:bytes_read", OIIO::TypeDesc::INT64, &bytes);
  ts->getattribute("stat:cache_memory_used", OIIO::TypeDesc::INT64, &memory);
  ts->getattribute("stat:tiles_created", tiles);
  ts->getattribute("stat:tiles_peak", peak);
  s.bytes_read = bytes;
  s.memory_bytes = memory;
  s.tiles_read = tiles;
  s.peak_tiles = peak;
  s.failed_lookups = impl_->failed.load();
  for (const Impl::Counts& c : impl_->counts) {
    s.lookups += c.lookups;
    s.lookup_seconds += c.seconds;
  }
  return s;
}

void TextureCache::reset_lookup_stats(bool timed) {
  impl_->counts.clear();
  impl_->timed = timed;
}

}  // namespace lantern
