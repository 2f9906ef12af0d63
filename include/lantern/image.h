// Images in and out of the renderer.
#pragma once

#include <string>
#include <utility>
#include <vector>

namespace lantern {

struct Image {
  int width = 0, height = 0;
  std::vector<float> rgb;  // linear, 3 floats per pixel, row 0 at the top
  // More channels of each pixel (pbrt-v4's gbuffer: "Albedo.R", "P.X",
  // ...), channel_names.size() floats a pixel; written to OpenEXR only.
  std::vector<std::string> channel_names;
  std::vector<float> channels;

  float* at(int x, int y) { return &rgb[3 * (size_t(y) * size_t(width) + size_t(x))]; }
  const float* at(int x, int y) const { return &rgb[3 * (size_t(y) * size_t(width) + size_t(x))]; }
};

using ImageMetadata = std::vector<std::pair<std::string, std::string>>;

// Writes through OpenImageIO; the format follows the extension. .exr and
// .hdr/.pfm keep linear floats; .png/.jpg/.tga get sRGB-encoded 8-bit.
// Written to a temporary file and renamed, so a failure never leaves a
// truncated image. Throws std::runtime_error with the reason.
void write_image(const std::string& path, const Image& image, const ImageMetadata& metadata);
// Whether write_image has a writer for path's extension.
bool can_write_image_format(const std::string& path);
// Linear values: float files as they are, integer files (8-bit PNG, JPEG,
// ...) decoded as image textures are (docs/textures.md: sRGB for 8 bits).
Image read_image(const std::string& path);
// The string attributes of an image's header whose names start with prefix.
ImageMetadata read_image_metadata(const std::string& path, const std::string& prefix = "lantern:");

}  // namespace lantern
