// The image module's functions (namespace lantern::oiio), gathered into the
// ImageIoModule table by oiio_module.cpp. Compiled into the module only.
#pragma once

#include "texture/image_io_module.h"

namespace lantern::oiio {

void write_image(const std::string& path, const Image& image, const ImageMetadata& metadata);
bool can_write_format(const std::string& path);
Image read_image(const std::string& path);
ImageMetadata read_image_metadata(const std::string& path, const std::string& prefix);
TextureImage load_texture_image(const std::string& path, ColorEncoding encoding);
std::pair<int, int> image_resolution(const std::string& path);
PreparedTexture prepare_texture(const std::string& source, ColorEncoding encoding, const std::string& directory);

void* cache_create(double max_memory_mb);
void cache_destroy(void* cache);
int32_t cache_add(void* cache, const std::string& path, ImageFilter filter, WrapMode wrap, float max_anisotropy);
bool cache_texture(void* cache, int32_t id, const TextureLookup& q, int first_channel, int channels, float* out);
TextureCacheStats cache_stats(void* cache);
void cache_reset_lookup_stats(void* cache, bool timed);

}  // namespace lantern::oiio
