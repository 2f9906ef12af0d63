#include "film/film.h"

#include <algorithm>
#include <numeric>
#include <stdexcept>
#include <string>

#include "film/pixel_filter.h"

namespace lantern {

Film::Film(int width, int height, const PixelFilter& filter)
    : width_(width),
      height_(height),
      filter_(filter),
      sum_(3 * size_t(width) * size_t(height)),
      count_(size_t(width) * size_t(height), 0),
      negative_(filter.is_signed() ? size_t(width) * size_t(height) : 0, 0) {}

namespace {

bool addable(const RGB& c) { return FixedSum::addable(c[0]) && FixedSum::addable(c[1]) && FixedSum::addable(c[2]); }

FixedTerm fixed_term(uint32_t pixel, const RGB& c, bool odd = false) {
  return FixedTerm{pixel, odd, {FixedSum::to_fixed(c[0]), FixedSum::to_fixed(c[1]), FixedSum::to_fixed(c[2])}};
}

// Flags of the film's state (write_state): which optional sums follow.
constexpr uint8_t kHasSplats = 1, kHasHalves = 2, kHasRegion = 4, kHasMoments = 8, kHasBuckets = 16, kHasNegatives = 32;

}  // namespace

// Every pixel whose filter support covers a splat's point gets the splat
// times the filter density at its offset: the same weight with which that
// pixel's own camera samples would have landed there.
void Film::set_sensor(const std::array<float, 9>& m) {
  sensor_ = m;
  has_sensor_ = m != std::array<float, 9>{1, 0, 0, 0, 1, 0, 0, 0, 1};
}

void Film::prepare(WaveOutput& out) const {
  out.sample_terms.clear();
  out.splat_terms.clear();
  out.nonfinite = 0;
  out.square_terms.clear();
  out.sample_terms.reserve(out.samples.size());
  for (const FilmSample& s : out.samples) {
    const RGB L = sensed(clamped(s.L));
    if (addable(L)) {
      out.sample_terms.push_back(fixed_term(s.pixel, s.negative ? -L : L, s.odd));
      // A square beyond the sums' range is left out of the moments alone.
      if (tracks_moments() && addable(L * L)) out.square_terms.push_back(fixed_term(s.pixel, L * L));
    } else {
      ++out.nonfinite;
    }
  }
  // (adaptive merging: into the sample sums of the pixels taking the pass)
  const bool per_pass = out.pass_light_paths > 0;
  const float pass_scale = per_pass ? float(pass_splat_scale(out.pass_light_paths)) : 1.f;
  std::vector<FixedTerm>& terms = per_pass ? out.sample_terms : out.splat_terms;
  for (const Splat& s : out.splats) {
    const RGB L = sensed(clamped(s.L)) * pass_scale;
    if (!addable(L)) {
      ++out.nonfinite;
      continue;
    }
    for_each_splat_pixel(filter_, width_, height_, s.p_raster - raster_offset(), [&](size_t pixel, float w) {
      if (!out.splat_pixels || out.splat_pixels[pixel]) terms.push_back(fixed_term(uint32_t(pixel), w * L, s.odd));
    });
  }
  if (buckets_.count > 0) prepare_buckets(out);
}

void Film::merge(const WaveOutput& out) {
  for (const FilmSample& s : out.samples) ++count_[s.pixel];
  if (!negative_.empty())
    for (const FilmSample& s : out.samples) negative_[s.pixel] += s.negative ? 1u : 0u;
  for (const FixedTerm& t : out.sample_terms)
    for (size_t c = 0; c < 3; ++c) sum_[3 * size_t(t.pixel) + c].add_raw(t.rgb[c]);
  if (!odd_.empty())
    for (const FixedTerm& t : out.sample_terms)
      if (t.odd)
        for (size_t c = 0; c < 3; ++c) odd_[3 * size_t(t.pixel) + c].add_raw(t.rgb[c]);
  if (!out.splat_terms.empty() && splat_.empty()) splat_.assign(sum_.size(), FixedSum());
  for (const FixedTerm& t : out.splat_terms)
    for (size_t c = 0; c < 3; ++c) splat_[3 * size_t(t.pixel) + c].add_raw(t.rgb[c]);
  if (!odd_.empty())
    for (const FixedTerm& t : out.splat_terms)
      if (t.odd)
        for (size_t c = 0; c < 3; ++c) odd_splat_[3 * size_t(t.pixel) + c].add_raw(t.rgb[c]);
  if (!square_.empty())
    for (const FixedTerm& t : out.square_terms)
      for (size_t c = 0; c < 3; ++c) square_[3 * size_t(t.pixel) + c].add_raw(t.rgb[c]);
  if (buckets_.count > 0) merge_buckets(out);
  nonfinite_ += out.nonfinite;
  light_paths_ += out.light_paths;
  odd_light_paths_ += out.odd_light_paths;
}

void Film::track_moments() {
  if (square_.empty()) square_.assign(sum_.size(), FixedSum());
}

double Film::sample_variance(size_t pixel, int c) const {
  const double n = double(count_[pixel]);
  if (square_.empty() || n < 2.0) return 0.0;
  const double sum = sum_[3 * pixel + size_t(c)].value(), sq = square_[3 * pixel + size_t(c)].value();
  return max_num(0.0, (sq - sum * sum / n) / (n - 1.0));
}

void Film::add(const Film& other) {
  if (other.width_ != width_ || other.height_ != height_)
    throw std::runtime_error("cannot add a " + std::to_string(other.width_) + "x" + std::to_string(other.height_) +
                             " film to a " + std::to_string(width_) + "x" + std::to_string(height_) + " one");
  for (size_t k = 0; k < sum_.size(); ++k) sum_[k].add(other.sum_[k]);
  if (!other.splat_.empty()) {
    if (splat_.empty()) splat_.assign(sum_.size(), FixedSum());
    for (size_t k = 0; k < splat_.size(); ++k) splat_[k].add(other.splat_[k]);
  }
  if (!other.odd_.empty()) {
    track_halves();
    for (size_t k = 0; k < odd_.size(); ++k) odd_[k].add(other.odd_[k]), odd_splat_[k].add(other.odd_splat_[k]);
    odd_light_paths_ += other.odd_light_paths_;
    // Adaptive sampling's measurements and choices, which a checkpoint
    // read into an empty film must bring (they are the film's, not sums:
    // adaptive sampling renders in one process, so no two films to add
    // both have them).
    if (thresholds_.empty() && !other.thresholds_.empty()) {
      thresholds_ = other.thresholds_;
      masks_ = other.masks_;
    }
  }
  if (!other.square_.empty()) {
    track_moments();
    for (size_t k = 0; k < square_.size(); ++k) square_[k].add(other.square_[k]);
  }
  if (other.buckets_.count > 0) add_buckets(other);
  for (size_t i = 0; i < count_.size(); ++i) count_[i] += other.count_[i];
  if (!other.negative_.empty()) {
    if (negative_.empty()) negative_.assign(count_.size(), 0);
    for (size_t i = 0; i < negative_.size(); ++i) negative_[i] += other.negative_[i];
  }
  nonfinite_ += other.nonfinite_;
  light_paths_ += other.light_paths_;
}

void Film::set_region(int x0, int y0, int full_width, int full_height) {
  x0_ = x0, y0_ = y0, full_width_ = full_width, full_height_ = full_height;
}

double splat_square_share(const PixelFilter& f) {
  // (on an image wide enough for every pixel a splat at its centre reaches)
  const int side = 2 * int(std::ceil(std::max(f.radius.x, f.radius.y))) + 3;
  constexpr int kGrid = 8;
  double sum = 0.0;
  for (int j = 0; j < kGrid; ++j)
    for (int i = 0; i < kGrid; ++i) {
      const Vec2 p(float(side / 2) + (float(i) + 0.5f) / kGrid, float(side / 2) + (float(j) + 0.5f) / kGrid);
      for_each_splat_pixel(f, side, side, p, [&](size_t, float w) { sum += double(w) * double(w); });
    }
  return sum / double(kGrid * kGrid);
}

double Film::splat_scale() const { return pass_splat_scale(light_paths_); }

double Film::pass_splat_scale(uint64_t light_paths) const {
  return light_paths ? image_pixels() / double(light_paths) : 0.0;
}

void Film::track_halves() {
  if (!odd_.empty()) return;
  odd_.assign(sum_.size(), FixedSum());
  odd_splat_.assign(sum_.size(), FixedSum());
  masks_.assign(2 * count_.size(), 1);
}

Film::Halves Film::halves(size_t pixel, int c) const {
  const size_t k = 3 * pixel + size_t(c);
  const uint32_t n = count_[pixel];
  const double n_odd = double(n / 2), n_even = double(n) - n_odd;
  const double sum = sum_[k].value(), odd = odd_[k].value();
  // (with signed samples each half is scaled by the pixel's share of
  // them: the halves' own signed counts are not kept)
  const double norm = sample_normalisation(pixel), share = n ? norm * double(n) : 0.0;
  Halves h{sum * norm, 0.0, 0.0};
  if (n >= 2) h.even = (sum - odd) / n_even * share, h.odd = odd / n_odd * share;
  if (!splat_.empty() && light_paths_ > 0) {
    // (over the whole image's pixels, as resolve: splat_scale)
    const double pixels = image_pixels();
    const double splat = splat_[k].value(), odd_splat = odd_splat_[k].value();
    const uint64_t even_paths = light_paths_ - odd_light_paths_;
    h.value += splat * pixels / double(light_paths_);
    if (n >= 2 && even_paths > 0 && odd_light_paths_ > 0)
      h.even += (splat - odd_splat) * pixels / double(even_paths),
          h.odd += odd_splat * pixels / double(odd_light_paths_);
  }
  return h;
}

Image Film::resolve() const {
  Image img;
  img.width = width_;
  img.height = height_;
  img.rgb.resize(sum_.size());
  const double splat_scale = this->splat_scale();
  for (size_t i = 0; i < count_.size(); ++i) {
    const double inv = sample_normalisation(i);
    for (int c = 0; c < 3; ++c) {
      size_t k = 3 * i + size_t(c);
      img.rgb[k] = float(sum_[k].value() * inv + (splat_.empty() ? 0.0 : splat_[k].value() * splat_scale));
    }
  }
  return img;
}

void Film::write_state(StateWriter& out) const {
  const int32_t size[2] = {width_, height_};
  out.write(size, sizeof size);
  out.write(&nonfinite_, sizeof nonfinite_);
  out.write(&light_paths_, sizeof light_paths_);
  const uint8_t flags = (splat_.empty() ? 0 : kHasSplats) | (odd_.empty() ? 0 : kHasHalves) |
                        (full_width_ > 0 ? kHasRegion : 0) | (square_.empty() ? 0 : kHasMoments) |
                        (buckets_.count > 0 ? kHasBuckets : 0) | (negative_.empty() ? 0 : kHasNegatives);
  out.write(&flags, 1);
  static_assert(sizeof(FixedSum) == sizeof(FixedSum::Raw));
  out.write(sum_.data(), sum_.size() * sizeof(FixedSum));
  out.write(count_.data(), count_.size() * sizeof(uint32_t));
  if (flags & kHasSplats) out.write(splat_.data(), splat_.size() * sizeof(FixedSum));
  if (flags & kHasRegion) {
    const int32_t region[4] = {x0_, y0_, full_width_, full_height_};
    out.write(region, sizeof region);
  }
  if (flags & kHasHalves) {
    out.write(odd_.data(), odd_.size() * sizeof(FixedSum));
    out.write(odd_splat_.data(), odd_splat_.size() * sizeof(FixedSum));
    out.write(&odd_light_paths_, sizeof odd_light_paths_);
    out.write(masks_.data(), masks_.size());
    const uint32_t n = uint32_t(thresholds_.size());
    out.write(&n, sizeof n);
    out.write(thresholds_.data(), n * sizeof(double));
  }
  if (flags & kHasMoments) out.write(square_.data(), square_.size() * sizeof(FixedSum));
  if (flags & kHasBuckets) write_buckets(out);
  if (flags & kHasNegatives) out.write(negative_.data(), negative_.size() * sizeof(uint32_t));
}

void Film::read_state(StateReader& in) {
  int32_t size[2];
  in.read(size, sizeof size);
  if (width_ == 0 && height_ == 0 && size[0] > 0 && size[1] > 0 && int64_t(size[0]) * size[1] <= (int64_t(1) << 28)) {
    width_ = size[0];
    height_ = size[1];
    sum_.assign(3 * size_t(width_) * size_t(height_), FixedSum());
    count_.assign(size_t(width_) * size_t(height_), 0);
  }
  if (size[0] != width_ || size[1] != height_)
    throw std::runtime_error("film state is " + std::to_string(size[0]) + "x" + std::to_string(size[1]) +
                             ", this film is " + std::to_string(width_) + "x" + std::to_string(height_));
  in.read(&nonfinite_, sizeof nonfinite_);
  in.read(&light_paths_, sizeof light_paths_);
  uint8_t flags = 0;
  in.read(&flags, 1);
  in.read(sum_.data(), sum_.size() * sizeof(FixedSum));
  in.read(count_.data(), count_.size() * sizeof(uint32_t));
  splat_.clear();
  if (flags & kHasSplats) {
    splat_.assign(sum_.size(), FixedSum());
    in.read(splat_.data(), splat_.size() * sizeof(FixedSum));
  }
  if (flags & kHasRegion) {
    int32_t region[4];
    in.read(region, sizeof region);
    if (region[0] < 0 || region[1] < 0 || region[2] < width_ || region[3] < height_ || region[0] > region[2] - width_ ||
        region[1] > region[3] - height_)
      throw std::runtime_error("film state: a crop that does not fit its image");
    set_region(region[0], region[1], region[2], region[3]);
  } else {
    set_region(0, 0, 0, 0);
  }
  const bool halves = !odd_.empty();  // (a film that tracks them keeps doing so)
  odd_.clear();
  odd_splat_.clear();
  masks_.clear();
  thresholds_.clear();
  odd_light_paths_ = 0;
  if (flags & kHasHalves) {
    track_halves();
    in.read(odd_.data(), odd_.size() * sizeof(FixedSum));
    in.read(odd_splat_.data(), odd_splat_.size() * sizeof(FixedSum));
    in.read(&odd_light_paths_, sizeof odd_light_paths_);
    in.read(masks_.data(), masks_.size());
    uint32_t n = 0;
    in.read(&n, sizeof n);
    if (n > (1u << 30)) throw std::runtime_error("film state: malformed adaptive sampling thresholds");
    thresholds_.resize(n);
    in.read(thresholds_.data(), n * sizeof(double));
  } else if (halves) {
    track_halves();
  }
  const bool moments = !square_.empty();  // (as the halves)
  square_.clear();
  if ((flags & kHasMoments) || moments) track_moments();
  if (flags & kHasMoments) in.read(square_.data(), square_.size() * sizeof(FixedSum));
  if (flags & kHasBuckets) {
    read_buckets(in);
  } else if (buckets_.count > 0) {  // (as the halves)
    bucket_sum_.assign(bucket_sum_.size(), FixedSum());
    bucket_splat_.clear();
  }
  const bool negatives = !negative_.empty();  // (as the halves)
  negative_.clear();
  if ((flags & kHasNegatives) || negatives) negative_.assign(count_.size(), 0);
  if (flags & kHasNegatives) in.read(negative_.data(), negative_.size() * sizeof(uint32_t));
}

Film::Buffers Film::buffers(bool splats) {
  if (splats && splat_.empty()) splat_.assign(sum_.size(), FixedSum());
  return Buffers{sum_.data(),   splat_.empty() ? nullptr : splat_.data(), sum_.size(), count_.data(),
                 negative_.empty() ? nullptr : negative_.data(), &nonfinite_, &light_paths_};
}

uint64_t Film::total_samples() const { return std::accumulate(count_.begin(), count_.end(), uint64_t(0)); }

uint32_t Film::max_samples_per_pixel() const {
  return count_.empty() ? 0 : *std::max_element(count_.begin(), count_.end());
}

uint32_t Film::min_samples_per_pixel() const {
  return count_.empty() ? 0 : *std::min_element(count_.begin(), count_.end());
}

}  // namespace lantern
