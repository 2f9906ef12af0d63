// Accumulates radiance per pixel. Camera samples land in the pixel they were
// taken for; light-tracing splats land wherever a light vertex projects and
// are spread over the pixels whose filter covers that point.
//
// Waves write into a WaveOutput of their own; the renderer merges outputs
// into the film one at a time in wave order, so every sum is formed in the
// same order whatever the thread count (bit-identical images).
#pragma once

#include <atomic>
#include <cstdint>
#include <vector>

#include "lantern/image.h"
#include "math/common.h"
#include "scene/scene.h"

namespace lantern {

struct FilmSample {
  uint32_t pixel;
  RGB L;
};
struct Splat {
  Vec2 p_raster;
  RGB L;  // contribution, already divided by nothing: the film normalises by the light-path count
};

struct WaveOutput {
  std::vector<FilmSample> samples;
  std::vector<Splat> splats;
  uint64_t light_paths = 0;
  void clear() {
    samples.clear();
    splats.clear();
    light_paths = 0;
  }
};

class Film {
 public:
  Film(int width, int height, const PixelFilter& filter);

  int width() const { return width_; }
  int height() const { return height_; }

  // Adds a wave's camera samples and splats. Not thread-safe: call in order.
  void merge(const WaveOutput& out);

  // pixel = (sum of its samples) / (its sample count)
  //       + (width * height / light paths) * (splats filtered onto it)
  Image resolve() const;
  uint64_t nonfinite_samples() const { return nonfinite_; }
  uint64_t total_samples() const;
  uint64_t light_paths() const { return light_paths_; }
  uint32_t min_samples_per_pixel() const;

 private:
  void add_splat(const Splat& s);

  int width_, height_;
  PixelFilter filter_;
  std::vector<double> sum_, splat_;
  std::vector<uint32_t> count_;
  uint64_t nonfinite_ = 0;
  uint64_t light_paths_ = 0;
};

}  // namespace lantern
