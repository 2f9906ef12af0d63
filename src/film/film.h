// Accumulates radiance samples per pixel. Each pixel keeps its own sample
// count, so a render stopped between waves still yields an unbiased image.
#pragma once

#include <atomic>
#include <cstdint>
#include <vector>

#include "lantern/image.h"
#include "math/common.h"

namespace lantern {

class Film {
 public:
  Film(int width, int height);

  int width() const { return width_; }
  int height() const { return height_; }

  // Adds a sample to a pixel. Only the task that owns the pixel's wave may
  // call it during a pass, so there is no race and the order of additions per
  // pixel is fixed by the sample index.
  void add_sample(uint32_t pixel, const RGB& L) {
    if (!is_finite(L)) {
      nonfinite_.fetch_add(1, std::memory_order_relaxed);
    } else {
      double* s = &sum_[3 * size_t(pixel)];
      s[0] += double(L.x);
      s[1] += double(L.y);
      s[2] += double(L.z);
    }
    ++count_[pixel];
  }

  Image resolve() const;
  uint64_t nonfinite_samples() const { return nonfinite_.load(); }
  uint64_t total_samples() const;
  uint32_t min_samples_per_pixel() const;

 private:
  int width_, height_;
  std::vector<double> sum_;
  std::vector<uint32_t> count_;
  std::atomic<uint64_t> nonfinite_{0};
};

}  // namespace lantern
