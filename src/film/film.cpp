#include "film/film.h"

#include <algorithm>
#include <numeric>
#include <stdexcept>
#include <string>

#include "film/pixel_filter.h"

namespace lantern {

Film::Film(int width, int height, const PixelFilter& filter)
    : width_(width), height_(height), filter_(filter), sum_(3 * size_t(width) * size_t(height), 0.0),
      count_(size_t(width) * size_t(height), 0) {}

void Film::merge(const WaveOutput& out) {
  for (const FilmSample& s : out.samples) {
    if (!is_finite(s.L)) {
      ++nonfinite_;
    } else {
      double* d = &sum_[3 * size_t(s.pixel)];
      d[0] += double(s.L.x);
      d[1] += double(s.L.y);
      d[2] += double(s.L.z);
    }
    ++count_[s.pixel];
  }
  if (!out.splats.empty() && splat_.empty()) splat_.assign(sum_.size(), 0.0);
  for (const Splat& s : out.splats) {
    if (!is_finite(s.L)) {
      ++nonfinite_;
      continue;
    }
    add_splat(s);
  }
  light_paths_ += out.light_paths;
}

// Every pixel whose filter support covers the point gets the splat times the
// filter density at its offset: the same weight with which that pixel's own
// camera samples would have landed there.
void Film::add_splat(const Splat& s) {
  for_each_splat_pixel(filter_, width_, height_, s.p_raster, [&](size_t pixel, float w) {
    double* d = &splat_[3 * pixel];
    d[0] += double(w * s.L.x);
    d[1] += double(w * s.L.y);
    d[2] += double(w * s.L.z);
  });
}

Image Film::resolve() const {
  Image img;
  img.width = width_;
  img.height = height_;
  img.rgb.resize(sum_.size());
  double splat_scale = light_paths_ ? double(width_) * double(height_) / double(light_paths_) : 0.0;
  for (size_t i = 0; i < count_.size(); ++i) {
    double inv = count_[i] ? 1.0 / double(count_[i]) : 0.0;
    for (int c = 0; c < 3; ++c) {
      size_t k = 3 * i + size_t(c);
      img.rgb[k] = float(sum_[k] * inv + (splat_.empty() ? 0.0 : splat_[k] * splat_scale));
    }
  }
  return img;
}

void Film::write_state(StateWriter& out) const {
  const int32_t size[2] = {width_, height_};
  out.write(size, sizeof size);
  out.write(&nonfinite_, sizeof nonfinite_);
  out.write(&light_paths_, sizeof light_paths_);
  const uint8_t has_splats = splat_.empty() ? 0 : 1;
  out.write(&has_splats, 1);
  out.write(sum_.data(), sum_.size() * sizeof(double));
  out.write(count_.data(), count_.size() * sizeof(uint32_t));
  if (has_splats) out.write(splat_.data(), splat_.size() * sizeof(double));
}

void Film::read_state(StateReader& in) {
  int32_t size[2];
  in.read(size, sizeof size);
  if (size[0] != width_ || size[1] != height_)
    throw std::runtime_error("film state is " + std::to_string(size[0]) + "x" + std::to_string(size[1]) +
                             ", this film is " + std::to_string(width_) + "x" + std::to_string(height_));
  in.read(&nonfinite_, sizeof nonfinite_);
  in.read(&light_paths_, sizeof light_paths_);
  uint8_t has_splats = 0;
  in.read(&has_splats, 1);
  in.read(sum_.data(), sum_.size() * sizeof(double));
  in.read(count_.data(), count_.size() * sizeof(uint32_t));
  splat_.clear();
  if (has_splats) {
    splat_.assign(sum_.size(), 0.0);
    in.read(splat_.data(), splat_.size() * sizeof(double));
  }
}

uint64_t Film::total_samples() const {
  return std::accumulate(count_.begin(), count_.end(), uint64_t(0));
}

uint32_t Film::min_samples_per_pixel() const {
  return count_.empty() ? 0 : *std::min_element(count_.begin(), count_.end());
}

}  // namespace lantern
