// Image textures as the texture cache reads them: tiled, MIP-mapped files of
// linear values. A file that already is one (an OpenEXR or TIFF texture made
// by maketx, or by Lantern before) is used where it is; any other image is
// decoded once (sRGB, gamma or linear, as the scene says), checked, and
// written as such a file into the texture directory, named by a hash of
// the source's path, size, modification time and encoding, so the next
// render of the scene reuses it. This is what a renderer's texture
// preprocessing step (maketx, txmake) does, done on demand at load.
#pragma once

#include <string>
#include <utility>

#include "texture/image.h"

namespace lantern {

struct PreparedTexture {
  std::string path;   // the file the texture cache opens
  int channels = 3;   // 1, 3 or 4 (RGBA), as in the source
  int width = 0, height = 0;
  bool converted = false;  // written into the texture directory by this call
  // The least and greatest value of any texel's channels (and alpha) as
  // the file holds them, which its MIP levels' averages and every filtered
  // lookup stay within: known for files Lantern prepared (recorded in the
  // file), unknown (empty) for a file used as it is.
  float least = kInfinity, greatest = -kInfinity;
};

// The resolution of an image file, read from its header; throws InputError
// naming the file if it cannot be read.
std::pair<int, int> image_resolution(const std::string& path);

// The texture directory when none is given: $XDG_CACHE_HOME/lantern/textures,
// else $HOME/.cache/lantern/textures, else a folder under /tmp.
std::string default_texture_directory();

// Throws InputError naming `source` for unreadable, empty, huge or
// non-finite images, and for a texture directory that cannot be written.
PreparedTexture prepare_texture(const std::string& source, ColorEncoding encoding, const std::string& directory);

}  // namespace lantern
