// Loads the image module on first use: from LANTERN_IMAGEIO_MODULE if set,
// else next to the running executable, else where the build put it.
#include <dlfcn.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

#include "texture/image_io_module.h"

namespace lantern {
namespace {

std::string executable_dir() {
  std::error_code ec;
  auto exe = std::filesystem::read_symlink("/proc/self/exe", ec);
  return ec ? std::string() : exe.parent_path().string();
}

const ImageIoModule* load_module() {
  std::vector<std::string> candidates;
  if (const char* env = std::getenv("LANTERN_IMAGEIO_MODULE"); env && *env) candidates.push_back(env);
  if (std::string dir = executable_dir(); !dir.empty()) candidates.push_back(dir + "/liblantern_imageio.so");
  candidates.push_back(LANTERN_IMAGEIO_MODULE_PATH);
  std::string tried;
  for (const std::string& path : candidates) {
    if (::access(path.c_str(), R_OK) != 0) {
      tried += "\n  " + path + ": not found";
      continue;
    }
    void* lib = ::dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
    if (!lib) {
      const char* why = ::dlerror();
      tried += "\n  " + path + ": " + (why ? why : "cannot load");
      continue;
    }
    using Entry = const ImageIoModule* (*)();
    auto entry = reinterpret_cast<Entry>(::dlsym(lib, "lantern_image_io_module"));
    const ImageIoModule* m = entry ? entry() : nullptr;
    if (m && m->version == kImageIoModuleVersion) return m;
    tried += "\n  " + path + ": not this version of Lantern's image module";
  }
  throw std::runtime_error("cannot load Lantern's image module (images are read and written through it):" + tried);
}

}  // namespace

const ImageIoModule& image_io_module() {
  static const ImageIoModule* module = load_module();  // thread-safe, once
  return *module;
}

}  // namespace lantern
