// Images in and out, through the image module (imageio/): OpenImageIO is
// loaded the first time an image is read or written.
#include "texture/image_io_module.h"
#include "lantern/image.h"

namespace lantern {

void write_image(const std::string& path, const Image& image, const ImageMetadata& metadata) {
  image_io_module().write_image(path, image, metadata);
}

bool can_write_image_format(const std::string& path) { return image_io_module().can_write_format(path); }

Image read_image(const std::string& path) { return image_io_module().read_image(path); }

ImageMetadata read_image_metadata(const std::string& path, const std::string& prefix) {
  return image_io_module().read_image_metadata(path, prefix);
}

}  // namespace lantern
