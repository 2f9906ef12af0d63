#include "texture/texture_cache.h"

#include <algorithm>

#include "texture/image_io_module.h"

namespace lantern {
namespace {

float sanitized(float v) { return std::isfinite(v) && v > 0.f ? v : 0.f; }

}  // namespace

TextureCache::TextureCache(const TextureCacheSettings& settings) : settings_(settings), io_(&image_io_module()) {
  if (settings_.directory.empty()) settings_.directory = default_texture_directory();
  handle_ = io_->cache_create(settings_.max_memory_mb);
}

TextureCache::~TextureCache() { io_->cache_destroy(handle_); }

int32_t TextureCache::add(const PreparedTexture& t, ImageFilter filter, WrapMode wrap, float max_anisotropy) {
  int32_t id = io_->cache_add(handle_, t.path, filter, wrap, max_anisotropy);
  // Lookups read negative values as 0 (sanitized) and alpha at most 1:
  // within [max(0, least), greatest] still.
  Entry e{t.channels, filter == ImageFilter::Point};
  if (t.least <= t.greatest) {
    e.least = std::max(t.least, 0.f);
    e.greatest = std::max(t.greatest, 0.f);
  }
  entries_.push_back(e);
  return id;
}

void TextureCache::texture(int32_t id, const TextureLookup& q, int first, int n, float* out) const {
  if (!io_->cache_texture(handle_, id, q, first, n, out))
    for (int i = 0; i < n; ++i) out[i] = 0.f;
}

RGB TextureCache::lookup_rgb(int32_t id, const TextureLookup& q) const {
  float v[3] = {0.f, 0.f, 0.f};
  if (entries_[size_t(id)].channels == 1) {
    texture(id, q, 0, 1, v);
    return RGB(sanitized(v[0]));
  }
  texture(id, q, 0, 3, v);
  return RGB(sanitized(v[0]), sanitized(v[1]), sanitized(v[2]));
}

float TextureCache::lookup_float(int32_t id, const TextureLookup& q) const {
  const Entry& e = entries_[size_t(id)];
  float v[3] = {0.f, 0.f, 0.f};
  if (e.point || e.channels == 1) {
    texture(id, q, 0, 1, v);
    return sanitized(v[0]);
  }
  if (e.channels == 4) {
    texture(id, q, 3, 1, v);
    return min_num(sanitized(v[0]), 1.f);
  }
  texture(id, q, 0, 3, v);
  return (sanitized(v[0]) + sanitized(v[1]) + sanitized(v[2])) / 3.f;
}

TextureCacheStats TextureCache::stats() const { return io_->cache_stats(handle_); }

void TextureCache::reset_lookup_stats(bool timed) { io_->cache_reset_lookup_stats(handle_, timed); }

}  // namespace lantern
