// A render's output files, checked before the render starts and written
// without losing the image at the end: a long render must not run to its
// end only to find that its image cannot be written.
#pragma once

#include <string>

#include "lantern/image.h"

namespace lantern {

// Throws std::runtime_error, naming the file and why, when a file cannot be
// created at path: its folder is missing or not writable. `what` names the
// file in the message ("the output image", "the checkpoint").
void check_writable(const std::string& path, const std::string& what);
// The same, and the extension must name an image format Lantern writes
// ("-", standard output, takes OpenEXR).
void check_image_path(const std::string& path);

// write_image, and for "-" the image as OpenEXR (linear floats, the whole
// header) on standard output. Throws std::runtime_error when it cannot.
void write_output_image(const std::string& path, const Image& image, const ImageMetadata& md);

struct ImageWrite {
  bool written = false;  // where asked
  std::string error;     // why not
  std::string rescue;    // where a rescue copy went instead ("" if none could be written)
};
// Writes the image at path. If that fails (a full disk, a removed folder),
// writes a rescue copy (EXR: every digit kept) next to the checkpoint, or
// in the working directory, or in the temporary directory.
ImageWrite write_image_or_rescue(const std::string& path, const Image& image, const ImageMetadata& md,
                                 const std::string& checkpoint_path);

}  // namespace lantern
