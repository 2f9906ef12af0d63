// Loads the image module on first use: from LANTERN_IMAGEIO_MODULE if set,
// else near the program that holds this code (the lantern command, a test,
// the Python module): next to it, one or two folders above it (the build
// folder, for programs in its subfolders), or in ../lib/lantern as
// `cmake --install` lays it out. No path of the build is compiled in, so an
// installed copy works wherever it is put and whatever became of the build.
#include <dlfcn.h>
#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

#include "texture/image_io_module.h"

namespace lantern {
namespace {

// Where to look: the folder of the shared object this code was linked into
// (the Python module; dladdr names a loaded library by its path), and the
// folder of the running executable (/proc/self/exe: for the main program
// dladdr gives only argv[0], which may be a bare name found on PATH).
std::vector<std::string> own_dirs() {
  std::vector<std::string> dirs;
  Dl_info info{};
  if (::dladdr(reinterpret_cast<void*>(&own_dirs), &info) && info.dli_fname &&
      std::strchr(info.dli_fname, '/') != nullptr) {
    std::error_code ec;
    const auto path = std::filesystem::canonical(info.dli_fname, ec);
    if (!ec) dirs.push_back(path.parent_path().string());
  }
  std::error_code ec;
  const auto exe = std::filesystem::read_symlink("/proc/self/exe", ec);
  // (in the main program both name the executable's folder: once is enough)
  if (!ec && std::find(dirs.begin(), dirs.end(), exe.parent_path().string()) == dirs.end())
    dirs.push_back(exe.parent_path().string());
  return dirs;
}

const ImageIoModule* load_module() {
  std::vector<std::string> candidates;
  if (const char* env = std::getenv("LANTERN_IMAGEIO_MODULE"); env && *env) candidates.push_back(env);
  for (const std::string& dir : own_dirs())
    for (const char* place : {"/", "/../lib/lantern/", "/../", "/../../"})  // installed before build-tree guesses
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
