// Images equal bit for bit: the same size and the same floats.
#pragma once

#include <cstring>

#include "lantern/image.h"

namespace lantern {

inline bool same_image(const Image& a, const Image& b) {
  return a.width == b.width && a.height == b.height && a.rgb.size() == b.rgb.size() &&
         std::memcmp(a.rgb.data(), b.rgb.data(), a.rgb.size() * sizeof(float)) == 0;
}

}  // namespace lantern
