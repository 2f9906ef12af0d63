// Moving a finished output into place. Outputs are written under a
// temporary name and renamed over their own, so that nobody reads half a
// file; but a name that is not a plain file (a symbolic link, a device such
// as /dev/stdout, a pipe) is written through instead: never renamed over,
// which would replace the link or the device with a file of ours.
// Header-only: the image module and the core both place outputs.
#pragma once

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>

namespace lantern {

// Whether path names something other than a plain file or nothing.
inline bool is_special_output(const std::string& path) {
  std::error_code ec;
  const auto st = std::filesystem::symlink_status(path, ec);
  if (ec || !std::filesystem::exists(st)) return false;
  return std::filesystem::is_symlink(st) || !std::filesystem::is_regular_file(st);
}

// Moves the finished file tmp to path (see above); tmp is gone afterwards.
// Throws std::runtime_error naming path.
inline void place_output(const std::string& tmp, const std::string& path) {
  std::error_code ec;
  if (is_special_output(path)) {
    bool ok;
    {
      std::ifstream in(tmp, std::ios::binary);
      std::ofstream out(path, std::ios::binary);
      ok = in && out && (out << in.rdbuf()) && out.flush();
    }
    std::remove(tmp.c_str());
    if (!ok) throw std::runtime_error("cannot write \"" + path + "\"");
    return;
  }
  std::filesystem::rename(tmp, path, ec);
  if (ec) {
    std::remove(tmp.c_str());
    throw std::runtime_error("cannot move the finished file to \"" + path + "\": " + ec.message());
  }
}

}  // namespace lantern
