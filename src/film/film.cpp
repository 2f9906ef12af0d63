#include "film/film.h"

#include <algorithm>
#include <numeric>

namespace lantern {

Film::Film(int width, int height)
    : width_(width), height_(height), sum_(3 * size_t(width) * size_t(height), 0.0),
      count_(size_t(width) * size_t(height), 0) {}

Image Film::resolve() const {
  Image img;
  img.width = width_;
  img.height = height_;
  img.rgb.resize(sum_.size());
  for (size_t i = 0; i < count_.size(); ++i) {
    double inv = count_[i] ? 1.0 / double(count_[i]) : 0.0;
    for (int c = 0; c < 3; ++c) img.rgb[3 * i + size_t(c)] = float(sum_[3 * i + size_t(c)] * inv);
  }
  return img;
}

uint64_t Film::total_samples() const {
  return std::accumulate(count_.begin(), count_.end(), uint64_t(0));
}

uint32_t Film::min_samples_per_pixel() const {
  return count_.empty() ? 0 : *std::min_element(count_.begin(), count_.end());
}

}  // namespace lantern
