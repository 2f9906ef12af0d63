// Accumulates radiance per pixel. Camera samples land in the pixel they were
// taken for; light-tracing splats land wherever a light vertex projects and
// are spread over the pixels whose filter covers that point.
//
// Waves write into a WaveOutput of their own and the renderer merges them
// into the film. The sums are fixed-point (math/fixed_sum.h), so they do not
// depend on the order of the terms: films of any pieces of a render, added,
// equal the film of the whole render bit for bit.
#pragma once

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#include "color/sampled_wavelengths.h"
#include "film/pixel_filter.h"
#include "guiding/guide_record.h"
#include "lantern/image.h"
#include "math/common.h"
#include "math/fixed_sum.h"
#include "math/state_io.h"

namespace lantern {

// Transported values arrive as the film's colour: an integrator turns each
// sample's spectrum into it with the sample's wavelengths (film_rgb,
// color/spectrum_conversion.h) when it records the sample.
struct FilmSample {
  uint32_t pixel;
  RGB L;
  bool odd = false;  // in the odd half of its pixel's samples (adaptive sampling's half-buffers: WaveDesc::odd)
  // Drawn where a filter with negative lobes is negative (pixel_filter.h):
  // it counts -1 in its pixel's signed count and its L is subtracted.
  bool negative = false;
};
struct Splat {
  Vec2 p_raster;
  RGB L;             // contribution, already divided by nothing: the film normalises by the light-path count
  bool odd = false;  // from the light path of a sample of the odd half
};

// One contribution of one bidirectional strategy (s light vertices, t eye
// vertices), kept only when per-strategy images are asked for. A merge
// (vcm) counts the merged vertex on both sides.
inline constexpr uint32_t kNoLight = ~0u;

struct StrategyRecord {
  uint32_t pixel;  // t >= 2: the pixel of the camera sample
  Vec2 p_raster;   // t = 1: where the splat lands
  uint8_t s, t;
  RGB weighted, unweighted;
  bool merge = false;
  // For the light subpath rate's pilot (integrator/light_subpath_rate.h):
  // the wave slot of the camera sample (t >= 2), the MIS weight, and the
  // part of its ratio sum that a change of the rate rescales.
  uint32_t slot = 0;
  float weight = 1.f, rescaled = 0.f;
  // The light the path ends at (an index into LightPools::all; kNoLight
  // when not known), whose share of light subpaths the pilot may change.
  uint32_t light = kNoLight;
};

// A sample's or splat's spectrum and wavelengths, kept beside it when the
// film has spectral buckets (Film "spectral").
struct SampleSpectrum {
  Spectrum L;
  SampledWavelengths lambda;
};

// pbrt-v4's Film "spectral": `count` buckets of equal width over
// [lambda_min, lambda_max] nm; count 0: none.
struct SpectralBuckets {
  int count = 0;
  float lambda_min = 360.f, lambda_max = 830.f;
  int bucket(float nm) const {
    const int b = int(float(count) * (nm - lambda_min) / (lambda_max - lambda_min));
    return std::clamp(b, 0, count - 1);
  }
  float centre(int b) const { return lambda_min + (float(b) + 0.5f) / float(count) * (lambda_max - lambda_min); }
};

// A spectral term of one pixel's bucket (pixel * count + bucket).
struct BucketTerm {
  uint32_t index;
  FixedSum::Raw value;
};

// A sample or a splat's share of one pixel, converted to fixed point.
struct FixedTerm {
  uint32_t pixel;
  bool odd;  // a camera sample of the odd half
  FixedSum::Raw rgb[3];
};

struct WaveOutput {
  std::vector<FilmSample> samples;
  std::vector<Splat> splats;
  std::vector<StrategyRecord> strategies;
  // With the strategies recorded (bdpt's pilot): per light
  // (LightPools::all), the rays its light subpaths cast (extensions and
  // connections of s >= 2: what the rate and the choice of light scale).
  std::vector<uint64_t> light_rays_by_light;
  uint64_t light_paths = 0, odd_light_paths = 0;
  // Adaptive merging (integrator/adaptive_sampling.h): set by the renderer,
  // > 0, the light paths of the wave's whole pass. The splats then count as
  // the pass's own estimate, scaled by the image's pixels over that number,
  // and only in the pixels that take the pass (`splat_pixels`, a byte a
  // pixel, null: all), in their sample sums: a pixel's splats are averaged
  // over the passes it takes, as its camera samples are.
  uint64_t pass_light_paths = 0;
  const uint8_t* splat_pixels = nullptr;
  std::vector<GuideRecord> guide;  // for the guiding field being learnt (integrator/guiding_field.h)
  std::vector<GuideRecord> light_guide;  // for its importance field (the light subpaths of bdpt and vcm)
  // Filled by Film::prepare from samples and splats, in the parallel stage,
  // so that the serial merge only adds integers.
  std::vector<FixedTerm> sample_terms, splat_terms;
  std::vector<FixedTerm> square_terms;  // the samples' squares, when the film tracks moments
  // Set by the renderer when the film has spectral buckets: each sample's
  // and splat's spectrum goes beside it, same index.
  bool keep_spectra = false;
  std::vector<SampleSpectrum> sample_spectra, splat_spectra;
  std::vector<BucketTerm> bucket_terms, bucket_splat_terms;
  // Set by Metropolis (integrator/metropolis.h): each splat's slot beside it.
  bool keep_slots = false;
  std::vector<uint32_t> splat_slots;
  uint64_t nonfinite = 0;
  void clear() {
    splat_slots.clear();
    sample_spectra.clear();
    splat_spectra.clear();
    bucket_terms.clear();
    bucket_splat_terms.clear();
    samples.clear();
    splats.clear();
    strategies.clear();
    light_rays_by_light.clear();
    guide.clear();
    light_guide.clear();
    light_paths = odd_light_paths = pass_light_paths = 0;
    splat_pixels = nullptr;
    sample_terms.clear();
    splat_terms.clear();
    square_terms.clear();
    nonfinite = 0;
  }
};

// Calls fn(pixel index, filter density) for every pixel whose filter support
// covers raster point p: the weights a splat at p is spread with.
template <class Fn>
void for_each_splat_pixel(const PixelFilter& f, int width, int height, Vec2 p, Fn&& fn);
// The sum of a splat's weights squared over the pixels it is spread on, on
// average over where in a pixel it lands: the share of a splat's square
// that lands in the pixels' variances (1 for a box filter of one pixel,
// 0.34 for pbrt-v4's default Gaussian), where a camera sample, drawn
// through the filter, adds its whole square to one pixel.
double splat_square_share(const PixelFilter& f);

class Film {
 public:
  Film(int width, int height, const PixelFilter& filter);

  int width() const { return width_; }
  int height() const { return height_; }
  // Where the film lies in the camera's image when it holds a part of it
  // (a crop): splats arrive in the camera's raster coordinates.
  void set_region(int x0, int y0, int full_width, int full_height);
  Vec2 raster_offset() const { return Vec2(float(x0_), float(y0_)); }
  bool cropped() const { return full_width_ > 0; }
  // The whole camera image's pixels, which splats are spread over.
  double image_pixels() const { return double(full_width()) * double(full_height()); }
  int full_width() const { return cropped() ? full_width_ : width_; }
  int full_height() const { return cropped() ? full_height_ : height_; }
  // What resolve multiplies the splat sums by: the whole image's pixels
  // over the light paths. A light path's expected splat on a pixel is the
  // pixel's value over the whole image's pixels (the camera's importance
  // spreads over all of them), however few pixels the film holds and
  // however few light paths it traced.
  double splat_scale() const;
  // What a pass's splats are scaled by when they go into the sample sums
  // (WaveOutput::pass_light_paths): the whole image's pixels over the
  // pass's light paths (splat_scale: over all of them).
  double pass_splat_scale(uint64_t light_paths) const;

  // The sensor every sample's colour passes through before it is added
  // (color/sensor.h): a 3x3 matrix on linear RGB, row-major. The identity
  // (the default) costs nothing.
  void set_sensor(const std::array<float, 9>& m);
  RGB sensed(const RGB& c) const {
    if (!has_sensor_) return c;
    const float* m = sensor_.data();
    return RGB(m[0] * c[0] + m[1] * c[1] + m[2] * c[2], m[3] * c[0] + m[4] * c[1] + m[5] * c[2],
               m[6] * c[0] + m[7] * c[1] + m[8] * c[2]);
  }

  // pbrt-v4's Film "maxcomponentvalue": a sample or splat whose largest
  // sensor component (rows of `to_sensor` times its linear RGB) exceeds
  // `value` is scaled so that it is `value`. Infinite: never (the default).
  void set_max_component(float value, const std::array<float, 9>& to_sensor) {
    max_component_ = value;
    to_sensor_ = to_sensor;
  }
  RGB clamped(const RGB& c) const {
    if (!(max_component_ < std::numeric_limits<float>::infinity())) return c;
    const float* m = to_sensor_.data();
    const float largest =
        max_num(m[0] * c[0] + m[1] * c[1] + m[2] * c[2],
                  max_num(m[3] * c[0] + m[4] * c[1] + m[5] * c[2], m[6] * c[0] + m[7] * c[1] + m[8] * c[2]));
    return largest > max_component_ ? c * (max_component_ / largest) : c;
  }

  // Converts a wave's samples and splats (filtered onto pixels) to
  // fixed-point terms, through the sensor. Thread-safe: waves call it in
  // parallel.
  void prepare(WaveOutput& out) const;

  // Adds a prepared wave's terms and sample counts. Not thread-safe.
  void merge(const WaveOutput& out);

  // Adds another film of the same size (a part, a rank, a checkpoint).
  void add(const Film& other);

  // pixel = (sum of its samples) / (its sample count)
  //       + (width * height / light paths) * (splats filtered onto it)
  Image resolve() const;
  uint64_t nonfinite_samples() const { return nonfinite_; }  // NaN, Inf, or beyond FixedSum's range
  uint64_t total_samples() const;
  uint64_t light_paths() const { return light_paths_; }
  uint32_t min_samples_per_pixel() const;
  uint32_t max_samples_per_pixel() const;
  uint32_t sample_count(size_t pixel) const { return count_[pixel]; }
  // What a pixel's sample sums are divided by: 1 / its samples, or with a
  // filter of negative lobes 1 / (its samples less twice its negative
  // ones), pbrt-v4's sum of filter weights (film/signed_filter.h); 0 when
  // that is 0.
  double sample_normalisation(size_t pixel) const {
    const int64_t n = negative_.empty() ? int64_t(count_[pixel]) : int64_t(count_[pixel]) - 2 * int64_t(negative_[pixel]);
    return n != 0 ? 1.0 / double(n) : 0.0;
  }

  // Adaptive sampling's half-buffers (integrator/adaptive_sampling.h): the
  // camera samples of the odd half (WaveDesc::odd: half of each pass's
  // sample indices) summed apart too, so that the means of the even and of
  // the odd ones can be compared. Off until asked for.
  void track_halves();
  bool tracks_halves() const { return !odd_.empty(); }
  // A pixel's value in channel c (what resolve gives), and the same from
  // the even and from the odd samples only (camera samples and the splats
  // of light paths of the even or the odd half, each normalised by its own
  // count); the halves' values are 0 until both halves have samples.
  struct Halves {
    double value, even, odd;
  };
  Halves halves(size_t pixel, int c) const;
  // What adaptive sampling measured at the end of each pass (its lambda
  // and image estimate, two values a pass), kept with the sums it was
  // measured from, so that a resumed render decides as the interrupted
  // one did.
  std::vector<double>& pass_measurements() { return thresholds_; }
  const std::vector<double>& pass_measurements() const { return thresholds_; }
  // Which pixels take pass p (p >= 2), decided at the end of pass p - 2:
  // one byte a pixel, two passes' worth (p mod 2), kept for a resume.
  uint8_t* pass_mask(uint32_t pass) { return masks_.data() + size_t(pass % 2) * count_.size(); }
  const uint8_t* pass_mask(uint32_t pass) const { return masks_.data() + size_t(pass % 2) * count_.size(); }

  // pbrt-v4's gbuffer variance: the camera samples' squares summed too, so
  // that each pixel's sample variance can be given. Off until asked for;
  // kept in the film's state, not in its Buffers (MPI).
  void track_moments();
  bool tracks_moments() const { return !square_.empty(); }
  // The unbiased variance of pixel i's camera samples in channel c (0 for
  // fewer than two); pbrt-v4's VarianceEstimator::Variance.
  double sample_variance(size_t pixel, int c) const;

  // pbrt-v4's Film "spectral" (film/spectral_buckets.cpp): each pixel's
  // radiance averaged over each bucket of wavelengths, times the integral
  // of y-bar, from the samples' and splats' spectra. Off until asked for;
  // kept in the film's state, not in its Buffers (MPI).
  void track_buckets(const SpectralBuckets& b);
  const SpectralBuckets& buckets() const { return buckets_; }
  // Appends the buckets to a resolved image as channels named as pbrt-v4
  // names them ("S0.<centre>nm", the centre with a decimal comma).
  void add_bucket_channels(Image* image) const;

  // The raw buffers, for adding films across processes (distributed/):
  // integers all, so any reduction order gives the same bits. With
  // `splats`, the splat sums are created if the film has none.
  struct Buffers {
    FixedSum* sums;
    FixedSum* splats;  // null when the film has none
    size_t values;     // of sums and of splats: 3 per pixel
    uint32_t* counts;     // one per pixel
    uint32_t* negatives;  // one per pixel; null unless the filter has negative lobes
    uint64_t* nonfinite;
    uint64_t* light_paths;
  };
  Buffers buffers(bool splats);
  bool has_splats() const { return !splat_.empty(); }

  // The raw sums and counts, bit for bit: a film restored from them goes on
  // accumulating exactly as the one that wrote them would have.
  void write_state(StateWriter& out) const;
  // The film must have the same size, or be 0x0: then it takes the state's
  // (up to 2^28 pixels).
  void read_state(StateReader& in);

 private:
  int width_, height_;
  int x0_ = 0, y0_ = 0, full_width_ = 0, full_height_ = 0;  // 0: the film is the whole image
  PixelFilter filter_;
  std::array<float, 9> sensor_{1, 0, 0, 0, 1, 0, 0, 0, 1};
  bool has_sensor_ = false;
  float max_component_ = std::numeric_limits<float>::infinity();
  std::array<float, 9> to_sensor_{1, 0, 0, 0, 1, 0, 0, 0, 1};
  std::vector<FixedSum> sum_, splat_, odd_, odd_splat_, square_;
  SpectralBuckets buckets_;
  std::vector<FixedSum> bucket_sum_, bucket_splat_;
  void prepare_buckets(WaveOutput& out) const;
  void merge_buckets(const WaveOutput& out);
  void add_buckets(const Film& other);
  void write_buckets(StateWriter& out) const;
  void read_buckets(StateReader& in);
  std::vector<double> thresholds_;
  std::vector<uint8_t> masks_;
  uint64_t odd_light_paths_ = 0;
  std::vector<uint32_t> count_;
  std::vector<uint32_t> negative_;  // per pixel, with a filter of negative lobes: its negative samples
  uint64_t nonfinite_ = 0;
  uint64_t light_paths_ = 0;
};

template <class Fn>
void for_each_splat_pixel(const PixelFilter& f, int width, int height, Vec2 p, Fn&& fn) {
  int x0 = std::max(0, int(std::ceil(p.x - 0.5f - f.radius.x)));
  int x1 = std::min(width - 1, int(std::floor(p.x - 0.5f + f.radius.x)));
  int y0 = std::max(0, int(std::ceil(p.y - 0.5f - f.radius.y)));
  int y1 = std::min(height - 1, int(std::floor(p.y - 0.5f + f.radius.y)));
  // The filter is separable: its column densities are looked up once per
  // splat, not once per pixel (unless the support is wider than the table).
  constexpr int kColumns = 32;
  float wx[kColumns];
  const bool tabulated = x1 - x0 < kColumns;
  if (tabulated)
    for (int x = x0; x <= x1; ++x) wx[x - x0] = pixel_filter_density_1d(f, p.x - (float(x) + 0.5f), 0);
  for (int y = y0; y <= y1; ++y) {
    float wy = pixel_filter_density_1d(f, p.y - (float(y) + 0.5f), 1);
    if (wy == 0.f) continue;
    for (int x = x0; x <= x1; ++x) {
      float w = wy * (tabulated ? wx[x - x0] : pixel_filter_density_1d(f, p.x - (float(x) + 0.5f), 0));
      if (w != 0.f) fn(size_t(y) * size_t(width) + size_t(x), w);
    }
  }
}

}  // namespace lantern
