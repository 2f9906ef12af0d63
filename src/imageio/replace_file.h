// Moving a finished output into place. Outputs are written under a
// temporary name and renamed over their own, so that nobody reads half a
// file; but a name that is not a plain file is never renamed over, which
// would replace it with a file of ours:
// - a symbolic link to a plain file (or to nothing yet): the file it names
//   is replaced, and the link stays;
// - a device such as /dev/stdout, or a pipe: the finished file is copied
//   into it, and its temporary file lives in the temporary directory, not
//   beside the device.
// Header-only: the image module and the core both place outputs.
#pragma once

#include <unistd.h>

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

// The plain file a name stands for: itself, or the end of its links when
// that is a plain file or nothing yet; empty for a device or a pipe.
inline std::string plain_output_file(const std::string& path) {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (!is_special_output(path)) return path;
  // Followed by the system first (it knows /proc's links to pipes).
  const auto st = fs::status(path, ec);
  if (fs::exists(st)) {
    if (!fs::is_regular_file(st)) return "";  // a device, a pipe, a socket
    const fs::path end = fs::canonical(path, ec);
    return ec ? "" : end.string();
  }
  // A link to nothing yet, followed by hand: its end names the file to create.
  fs::path p(path);
  for (int links = 0; links < 16; ++links) {
    if (!fs::is_symlink(fs::symlink_status(p, ec))) return p.string();
    const fs::path target = fs::read_symlink(p, ec);
    if (ec) return "";
    p = target.is_relative() ? p.parent_path() / target : target;
  }
  return "";  // a loop of links: written through, which fails with its reason
}

// Where to write path's output before moving it there: beside the plain
// file it stands for, or in the temporary directory for a device or pipe.
// `suffix` ends the name (an image writer picks its format from it).
inline std::string temporary_output(const std::string& path, const std::string& suffix) {
  const std::string plain = plain_output_file(path);
  std::filesystem::path p(plain.empty() ? path : plain);
  std::filesystem::path dir = plain.empty() ? std::filesystem::temp_directory_path() : p.parent_path();
  return (dir / ("." + p.stem().string() + "." + std::to_string(::getpid()) + ".partial" + suffix)).string();
}

// Moves the finished file tmp (from temporary_output) to path; tmp is gone
// afterwards. Throws std::runtime_error naming path.
inline void place_output(const std::string& tmp, const std::string& path) {
  std::error_code ec;
  const std::string plain = plain_output_file(path);
  if (plain.empty()) {  // a device or a pipe: written through
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
  std::filesystem::rename(tmp, plain, ec);
  if (ec) {
    std::remove(tmp.c_str());
    throw std::runtime_error("cannot move the finished file to \"" + path + "\": " + ec.message());
  }
}

}  // namespace lantern
