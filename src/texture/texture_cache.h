// Image textures read through OpenImageIO's TextureSystem: tiles of
// prepared (tiled, MIP-mapped, linear) files are loaded on demand into one
// cache with a memory limit and evicted when it is full, so a scene with
// hundreds of large textures renders in bounded memory. Each registered
// texture keeps its lookup options (filter, wrap, anisotropy), built once.
// The TextureSystem lives in the image module (imageio/); this class holds
// its handle and pbrt-v4's reading of channels.
#pragma once

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "texture/image.h"
#include "texture/prepared_texture.h"

namespace lantern {

struct TextureCacheSettings {
  double max_memory_mb = 1024.0;  // OpenImageIO's own default
  std::string directory;         // for prepared files; empty: default_texture_directory()
};

// Where a lookup lands: (s, t) with t = 0 at the image's top row, and
// their derivatives over a pixel step in x and y (zero: no footprint).
struct TextureLookup {
  Vec2 st{0.f};
  Vec2 dst_dx{0.f}, dst_dy{0.f};
};

struct TextureCacheStats {
  int64_t bytes_read = 0;      // texel bytes read from prepared files (a tile read again counts again)
  int64_t tiles_read = 0;
  int64_t peak_tiles = 0;      // held in the cache at once
  int64_t memory_bytes = 0;    // of tiles held in the cache now
  int64_t failed_lookups = 0;  // a file that could not be read during the render (read as 0)
  int64_t lookups = 0;         // since the last reset
  double lookup_seconds = 0.0; // thread-seconds in lookups, when timed
};

class TextureCache {
 public:
  explicit TextureCache(const TextureCacheSettings& settings);
  ~TextureCache();
  TextureCache(const TextureCache&) = delete;
  TextureCache& operator=(const TextureCache&) = delete;

  const TextureCacheSettings& settings() const { return settings_; }
  // Registers a prepared texture with its lookup options; returns its id.
  int32_t add(const PreparedTexture& t, ImageFilter filter, WrapMode wrap, float max_anisotropy);
  // The least and greatest value any lookup of texture id reads where its
  // file is read (a failed read gives 0), as the prepared file recorded
  // them; lo > hi where they are not known.
  std::pair<float, float> bounds(int32_t id) const {
    const Entry& e = entries_[size_t(id)];
    return {e.least, e.greatest};
  }

  // pbrt-v4's lookups: a float lookup reads a grey file's value, the mean
  // of RGB, or an RGBA file's alpha (point lookups: the first channel).
  // Non-finite or negative values read as 0.
  RGB lookup_rgb(int32_t id, const TextureLookup& q) const;
  float lookup_float(int32_t id, const TextureLookup& q) const;

  TextureCacheStats stats() const;
  // Zeroes the lookup counts and, with timed, clocks every lookup (two
  // clock reads each: for --stats only).
  void reset_lookup_stats(bool timed);

 private:
  struct Entry {
    int channels = 3;
    bool point = false;
    float least = kInfinity, greatest = -kInfinity;  // PreparedTexture's, lookups' sanitizing applied
  };
  // n channels from `first` into out; zeros where the file failed.
  void texture(int32_t id, const TextureLookup& q, int first, int n, float* out) const;

  TextureCacheSettings settings_;
  const struct ImageIoModule* io_ = nullptr;
  void* handle_ = nullptr;  // the module's cache
  std::vector<Entry> entries_;
};

}  // namespace lantern
