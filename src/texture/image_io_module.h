// The boundary between Lantern and its image module, liblantern_imageio.so:
// the only code that uses OpenImageIO (src/imageio/oiio_*.cpp). The
// module is loaded on first use (image_io_loader.cpp), so a run that reads and
// writes no image (--help, a render that fails at load, a benchmark of the
// core) never loads OpenImageIO and the ~260 libraries Debian's build pulls
// in at start-up. One table of functions, filled by the module; both sides
// are built together, and the version guards against a stale module.
#pragma once

#include <string>
#include <utility>

#include "lantern/image.h"
#include "texture/image.h"
#include "texture/prepared_texture.h"
#include "texture/texture_cache.h"

namespace lantern {

inline constexpr int kImageIoModuleVersion = 2;

struct ImageIoModule {
  int version;
  // lantern/image.h
  void (*write_image)(const std::string& path, const Image& image, const ImageMetadata& metadata);
  bool (*can_write_format)(const std::string& path);
  Image (*read_image)(const std::string& path);
  ImageMetadata (*read_image_metadata)(const std::string& path, const std::string& prefix);
  // texture/image.h and texture/prepared_texture.h
  TextureImage (*load_texture_image)(const std::string& path, ColorEncoding encoding);
  std::pair<int, int> (*image_resolution)(const std::string& path);
  PreparedTexture (*prepare_texture)(const std::string& source, ColorEncoding encoding, const std::string& directory);
  // texture/texture_cache.h: an OpenImageIO TextureSystem behind a handle.
  // Lookups return false (and count a failure) when the file cannot be read.
  void* (*cache_create)(double max_memory_mb);
  void (*cache_destroy)(void* cache);
  int32_t (*cache_add)(void* cache, const std::string& path, ImageFilter filter, WrapMode wrap, float max_anisotropy);
  bool (*cache_texture)(void* cache, int32_t id, const TextureLookup& q, int first_channel, int channels, float* out);
  TextureCacheStats (*cache_stats)(void* cache);
  void (*cache_reset_lookup_stats)(void* cache, bool timed);
};

// The module, loaded on the first call; throws std::runtime_error naming
// the places it looked when it cannot be loaded.
const ImageIoModule& image_io_module();

}  // namespace lantern

// The module's one exported symbol.
extern "C" const lantern::ImageIoModule* lantern_image_io_module();
