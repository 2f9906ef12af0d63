// Loads the image module on first use: from LANTERN_IMAGEIO_MODULE if set,
// else near the program that holds this code (the lantern command, a test,
// the Python module): next to it, one or two folders above it (the build
// folder, for programs in its subfolders), or in ../lib/lantern as
// `cmake --install` lays it out. No path of the build is compiled in, so an
// installed copy works wherever it is put and whatever became of the build.
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

// The folder of the executable or shared object this code was linked into.
std::string own_dir() {
  Dl_info info{};
  if (::dladdr(reinterpret_cast<void*>(&own_dir), &info) && info.dli_fname && *info.dli_fname) {
    std::error_code ec;
    auto path = std::filesystem::canonical(info.dli_fname, ec);
    if (!ec) return path.parent_path().string();
  }
  std::error_code ec;
  auto exe = std::filesystem::read_symlink("/proc/self/exe", ec);
  return ec ? std::string() : exe.parent_path().string();
}

const ImageIoModule* load_module() {
  std::vector<std::string> candidates;
  if (const char* env = std::getenv("LANTERN_IMAGEIO_MODULE"); env && *env) candidates.push_back(env);
  if (const std::string dir = own_dir(); !dir.empty())
    for (const char* place : {"/", "/../", "/../../", "/../lib/lantern/"})
      candidates.push_back(dir + place + "liblantern_imageio.so");
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
