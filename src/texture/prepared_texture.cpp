#include "texture/prepared_texture.h"

#include <unistd.h>

#include <cstdlib>
#include <filesystem>

#include "texture/image_io_module.h"

namespace lantern {
namespace fs = std::filesystem;

std::string default_texture_directory() {
  if (const char* x = std::getenv("XDG_CACHE_HOME"); x && *x) return (fs::path(x) / "lantern" / "textures").string();
  if (const char* h = std::getenv("HOME"); h && *h) return (fs::path(h) / ".cache" / "lantern" / "textures").string();
  return (fs::temp_directory_path() / ("lantern-textures-" + std::to_string(::getuid()))).string();
}

std::pair<int, int> image_resolution(const std::string& path) { return image_io_module().image_resolution(path); }

PreparedTexture prepare_texture(const std::string& source, ColorEncoding encoding, const std::string& directory) {
  return image_io_module().prepare_texture(source, encoding, directory);
}

}  // namespace lantern
