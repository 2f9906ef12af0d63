// Accumulates radiance per pixel. Camera samples land in the pixel they were
// taken for; light-tracing splats land wherever a light vertex projects and
// are spread over the pixels whose filter covers that point.
//
// Waves write into a WaveOutput of their own; the renderer merges outputs
// into the film one at a time in wave order, so every sum is formed in the
// same order whatever the thread count (bit-identical images).
#pragma once

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <vector>

#include "lantern/image.h"
#include "math/common.h"
#include "film/pixel_filter.h"

namespace lantern {

struct FilmSample {
  uint32_t pixel;
  RGB L;
};
struct Splat {
  Vec2 p_raster;
  RGB L;  // contribution, already divided by nothing: the film normalises by the light-path count
};

// One contribution of one bidirectional strategy (s light vertices, t eye
// vertices), kept only when per-strategy images are asked for.
struct StrategyRecord {
  uint32_t pixel;  // t >= 2: the pixel of the camera sample
  Vec2 p_raster;   // t = 1: where the splat lands
  uint8_t s, t;
  RGB weighted, unweighted;
};

struct WaveOutput {
  std::vector<FilmSample> samples;
  std::vector<Splat> splats;
  std::vector<StrategyRecord> strategies;
  uint64_t light_paths = 0;
  void clear() {
    samples.clear();
    splats.clear();
    strategies.clear();
    light_paths = 0;
  }
};

// Calls fn(pixel index, filter density) for every pixel whose filter support
// covers raster point p: the weights a splat at p is spread with.
template <class Fn>
void for_each_splat_pixel(const PixelFilter& f, int width, int height, Vec2 p, Fn&& fn);

// Byte sinks and sources for Film::write_state / read_state (checkpoints).
class StateWriter {
 public:
  virtual void write(const void* bytes, size_t n) = 0;

 protected:
  ~StateWriter() = default;
};
class StateReader {
 public:
  virtual void read(void* bytes, size_t n) = 0;  // throws if the source ends early

 protected:
  ~StateReader() = default;
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
  uint32_t sample_count(size_t pixel) const { return count_[pixel]; }

  // The raw sums and counts, bit for bit: a film restored from them goes on
  // accumulating exactly as the one that wrote them would have.
  void write_state(StateWriter& out) const;
  void read_state(StateReader& in);  // the film must have the same size

 private:
  void add_splat(const Splat& s);

  int width_, height_;
  PixelFilter filter_;
  std::vector<double> sum_, splat_;
  std::vector<uint32_t> count_;
  uint64_t nonfinite_ = 0;
  uint64_t light_paths_ = 0;
};

template <class Fn>
void for_each_splat_pixel(const PixelFilter& f, int width, int height, Vec2 p, Fn&& fn) {
  int x0 = std::max(0, int(std::ceil(p.x - 0.5f - f.radius.x)));
  int x1 = std::min(width - 1, int(std::floor(p.x - 0.5f + f.radius.x)));
  int y0 = std::max(0, int(std::ceil(p.y - 0.5f - f.radius.y)));
  int y1 = std::min(height - 1, int(std::floor(p.y - 0.5f + f.radius.y)));
  for (int y = y0; y <= y1; ++y) {
    float wy = pixel_filter_density_1d(f, p.y - (float(y) + 0.5f), 1);
    if (wy == 0.f) continue;
    for (int x = x0; x <= x1; ++x) {
      float w = wy * pixel_filter_density_1d(f, p.x - (float(x) + 0.5f), 0);
      if (w != 0.f) fn(size_t(y) * size_t(width) + size_t(x), w);
    }
  }
}

}  // namespace lantern
