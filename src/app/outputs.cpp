#include "app/outputs.h"

#include "imageio/replace_file.h"

#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <vector>
#include <unistd.h>

namespace lantern {

namespace fs = std::filesystem;

void check_writable(const std::string& path, const std::string& what) {
  if (path == "-") return;  // standard output
  // A device or pipe is written through where it is, and checked without
  // opening it (opening a pipe would block); a link, where it leads
  // (imageio/replace_file.h).
  const std::string plain = plain_output_file(path);
  if (plain.empty()) {
    if (::access(path.c_str(), W_OK) != 0)
      throw std::runtime_error("cannot write " + what + " \"" + path + "\": " + std::strerror(errno));
    return;
  }
  const fs::path p(plain);
  const fs::path dir = p.parent_path().empty() ? fs::path(".") : p.parent_path();
  std::error_code ec;
  if (!fs::is_directory(dir, ec))
    throw std::runtime_error("cannot write " + what + " \"" + path + "\": the folder \"" + dir.string() +
                             "\" does not exist");
  if (fs::is_directory(p, ec)) throw std::runtime_error("cannot write " + what + " \"" + path + "\": it is a folder");
  // A file of our own next to it, created and removed: the real test of a
  // writable folder (permissions, read-only mounts, quotas at zero).
  const fs::path probe = dir / (".lantern-probe-" + std::to_string(getpid()));
  {
    std::ofstream f(probe);
    if (!f) {
      const std::string why = std::strerror(errno);
      throw std::runtime_error("cannot write " + what + " \"" + path + "\": cannot create files in \"" +
                               dir.string() + "\" (" + why + ")");
    }
  }
  fs::remove(probe, ec);
}

void check_image_path(const std::string& path) {
  check_writable(path, "the output image");
  if (path == "-") return;
  if (!can_write_image_format(path))
    throw std::runtime_error("cannot write the output image \"" + path + "\": no image writer for the extension \"" +
                             fs::path(path).extension().string() + "\"; use .exr (linear floats) or .png");
}

void write_output_image(const std::string& path, const Image& image, const ImageMetadata& md) {
  if (path != "-") return write_image(path, image, md);
  // The writers take file names: a file of our own in the temporary
  // folder, copied to standard output and removed.
  std::string tmp = (fs::temp_directory_path() / "lantern-stdout-XXXXXX.exr").string();
  const int fd = ::mkstemps(tmp.data(), 4);
  if (fd < 0) throw std::runtime_error(std::string("cannot write the image to standard output: ") + std::strerror(errno));
  ::close(fd);
  struct Remove {
    std::string path;
    ~Remove() { std::remove(path.c_str()); }
  } remove{tmp};
  write_image(tmp, image, md);
  std::FILE* in = std::fopen(tmp.c_str(), "rb");
  if (!in) throw std::runtime_error("cannot read back " + tmp + ": " + std::strerror(errno));
  char buf[1 << 16];
  size_t n = 0;
  bool ok = true;
  while (ok && (n = std::fread(buf, 1, sizeof buf, in)) > 0) ok = std::fwrite(buf, 1, n, stdout) == n;
  std::fclose(in);
  if (!ok || std::fflush(stdout) != 0)
    throw std::runtime_error(std::string("cannot write the image to standard output: ") + std::strerror(errno));
}

ImageWrite write_image_or_rescue(const std::string& path, const Image& image, const ImageMetadata& md,
                                 const std::string& checkpoint_path) {
  ImageWrite w;
  try {
    write_output_image(path, image, md);
    w.written = true;
    return w;
  } catch (const std::exception& e) {
    w.error = e.what();
  }
  const std::string name = (path == "-" ? std::string("stdout") : fs::path(path).stem().string()) + ".rescue.exr";
  std::vector<fs::path> places;
  if (!checkpoint_path.empty()) places.push_back(fs::path(checkpoint_path).parent_path());
  places.push_back(fs::current_path());
  places.push_back(fs::temp_directory_path());
  for (const fs::path& dir : places) {
    const fs::path rescue = (dir.empty() ? fs::path(".") : dir) / name;
    try {
      write_image(rescue.string(), image, md);
      w.rescue = rescue.string();
      return w;
    } catch (const std::exception&) {
      // the next place
    }
  }
  return w;
}

}  // namespace lantern
