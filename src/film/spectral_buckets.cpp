// pbrt-v4's Film "spectral": beside its RGB, each pixel keeps its radiance
// in `count` buckets of wavelength, written as the OpenEXR spectral layout
// of Fichet et al. 2021 ("An OpenEXR Layout for Spectral Images", JCGT
// 10(3)) names them.
//
// What a bucket holds: the pixel's spectral radiance averaged over the
// bucket's wavelengths, times the integral of y-bar (pbrt-v4's
// CIE_Y_integral, which undoes the normalisation of light spectra to unit
// luminance, so a white light of luminance 1 gives buckets of about 1).
// Each wavelength i of a sample, drawn with density p_i, lands in its
// bucket b as
//     Y_int * L_i / (p_i * n * width_b),
// n the wavelengths a sample carries: summed over a pixel's samples and
// divided by their count, the expected value is Y_int times the integral of
// L over the bucket over its width, for any density (the film draws them
// uniformly over its range, as pbrt-v4 does; a wavelength whose density is
// zero, ended by dispersion, adds nothing and the first's density counts
// for it). Splats are spread as their RGB is and scaled as it is.
//
// pbrt-v4 instead divides each bucket by the count of wavelengths that
// fell in it (the same in expectation for camera samples), and adds splats
// (bdpt's t = 1) with another factor, so its light-tracing strategy's
// buckets are off by Y_int over the bucket width; here every strategy's
// buckets are the same quantity (tests/spectral_film_test.cpp).
#include <cstdio>
#include <stdexcept>
#include <string>

#include "film/film.h"

namespace lantern {

namespace {

// pbrt-v4's CIE_Y_integral: the integral of the CIE 1931 y-bar over
// 360-830 nm at 1 nm.
constexpr float kCieYIntegral = 106.856895f;

// pbrt-v4's spectral clamp: a spectrum whose largest value exceeds the
// film's "maxcomponentvalue" is scaled down to it.
Spectrum clamped_spectrum(const Spectrum& L, float max_component) {
  float largest = L[0];
  for (int i = 1; i < kSpectrumSamples; ++i) largest = max_num(largest, L[i]);
  return largest > max_component ? L * (max_component / largest) : L;
}

// Calls fn(bucket, value) for each wavelength of the sample that counts.
template <class Fn>
void for_each_bucket_value(const SpectralBuckets& b, const SampleSpectrum& s, float max_component, Fn&& fn) {
  const Spectrum L = clamped_spectrum(s.L, max_component);
  const float width = (b.lambda_max - b.lambda_min) / float(b.count);
  for (int i = 0; i < kSpectrumSamples; ++i) {
    const float pdf = s.lambda.pdf[size_t(i)];
    if (!(pdf > 0.f)) continue;
    const float v = kCieYIntegral * L[i] / (pdf * float(kSpectrumSamples) * width);
    if (FixedSum::addable(v)) fn(b.bucket(s.lambda.nm[size_t(i)]), v);
  }
}

}  // namespace

void Film::track_buckets(const SpectralBuckets& b) {
  if (b.count <= 0 || !(b.lambda_min < b.lambda_max))
    throw std::invalid_argument("spectral buckets need a count > 0 and a wavelength range");
  if (count_.size() * size_t(b.count) > size_t(UINT32_MAX))
    throw std::invalid_argument("too many pixels times spectral buckets (over 2^32): fewer \"nbuckets\" or pixels");
  buckets_ = b;
  bucket_sum_.assign(count_.size() * size_t(b.count), FixedSum());
  bucket_splat_.clear();
}

void Film::prepare_buckets(WaveOutput& out) const {
  out.bucket_terms.clear();
  out.bucket_splat_terms.clear();
  if (out.sample_spectra.size() != out.samples.size() || out.splat_spectra.size() != out.splats.size())
    throw std::logic_error("a wave's spectra do not match its samples and splats");
  const size_t n = size_t(buckets_.count);
  for (size_t k = 0; k < out.samples.size(); ++k)
    for_each_bucket_value(buckets_, out.sample_spectra[k], max_component_, [&](int b, float v) {
      out.bucket_terms.push_back(
          {uint32_t(size_t(out.samples[k].pixel) * n + size_t(b)), FixedSum::to_fixed(out.samples[k].negative ? -v : v)});
    });
  // (adaptive merging: into the sample sums, as Film::prepare)
  const bool per_pass = out.pass_light_paths > 0;
  const float pass_scale = per_pass ? float(pass_splat_scale(out.pass_light_paths)) : 1.f;
  std::vector<BucketTerm>& terms = per_pass ? out.bucket_terms : out.bucket_splat_terms;
  for (size_t k = 0; k < out.splats.size(); ++k)
    for_each_bucket_value(buckets_, out.splat_spectra[k], max_component_, [&](int b, float v) {
      for_each_splat_pixel(
          filter_, width_, height_, out.splats[k].p_raster - raster_offset(), [&](size_t pixel, float w) {
            if (!out.splat_pixels || out.splat_pixels[pixel])
              terms.push_back({uint32_t(pixel * n + size_t(b)), FixedSum::to_fixed(w * v * pass_scale)});
          });
    });
}

void Film::merge_buckets(const WaveOutput& out) {
  for (const BucketTerm& t : out.bucket_terms) bucket_sum_[t.index].add_raw(t.value);
  if (!out.bucket_splat_terms.empty() && bucket_splat_.empty()) bucket_splat_.assign(bucket_sum_.size(), FixedSum());
  for (const BucketTerm& t : out.bucket_splat_terms) bucket_splat_[t.index].add_raw(t.value);
}

void Film::add_buckets(const Film& other) {
  if (buckets_.count == 0) track_buckets(other.buckets_);
  if (other.buckets_.count != buckets_.count || other.buckets_.lambda_min != buckets_.lambda_min ||
      other.buckets_.lambda_max != buckets_.lambda_max)
    throw std::runtime_error("cannot add films of different spectral buckets");
  for (size_t k = 0; k < bucket_sum_.size(); ++k) bucket_sum_[k].add(other.bucket_sum_[k]);
  if (!other.bucket_splat_.empty()) {
    if (bucket_splat_.empty()) bucket_splat_.assign(bucket_sum_.size(), FixedSum());
    for (size_t k = 0; k < bucket_splat_.size(); ++k) bucket_splat_[k].add(other.bucket_splat_[k]);
  }
}

void Film::add_bucket_channels(Image* image) const {
  if (buckets_.count == 0) return;
  const size_t n = size_t(buckets_.count), pixels = count_.size();
  const size_t first = image->channel_names.size(), stride = first + n;
  for (int b = 0; b < buckets_.count; ++b) {
    char name[32];
    std::snprintf(name, sizeof name, "%.3fnm", double(buckets_.centre(b)));
    std::string s = name;
    for (char& c : s)
      if (c == '.') c = ',';  // OpenEXR separates layers by full stops
    image->channel_names.push_back("S0." + s);
  }
  // Interleave with the channels the image already has.
  std::vector<float> channels(pixels * stride, 0.f);
  for (size_t i = 0; i < pixels && first > 0; ++i)
    std::copy_n(&image->channels[i * first], first, &channels[i * stride]);
  const double splat_scale = this->splat_scale();
  for (size_t i = 0; i < pixels; ++i) {
    const double inv = sample_normalisation(i);
    for (size_t b = 0; b < n; ++b) {
      const size_t k = i * n + b;
      channels[i * stride + first + b] =
          float(bucket_sum_[k].value() * inv + (bucket_splat_.empty() ? 0.0 : bucket_splat_[k].value() * splat_scale));
    }
  }
  image->channels = std::move(channels);
}

void Film::write_buckets(StateWriter& out) const {
  const int32_t count = buckets_.count;
  const float range[2] = {buckets_.lambda_min, buckets_.lambda_max};
  const uint8_t has_splats = bucket_splat_.empty() ? 0 : 1;
  out.write(&count, sizeof count);
  out.write(range, sizeof range);
  out.write(&has_splats, 1);
  out.write(bucket_sum_.data(), bucket_sum_.size() * sizeof(FixedSum));
  if (has_splats) out.write(bucket_splat_.data(), bucket_splat_.size() * sizeof(FixedSum));
}

void Film::read_buckets(StateReader& in) {
  int32_t count = 0;
  float range[2];
  uint8_t has_splats = 0;
  in.read(&count, sizeof count);
  in.read(range, sizeof range);
  in.read(&has_splats, 1);
  if (count < 1 || count > 4096 || !(range[0] < range[1]))
    throw std::runtime_error("film state: malformed spectral buckets");
  if (buckets_.count > 0 && (count != buckets_.count || range[0] != buckets_.lambda_min || range[1] != buckets_.lambda_max))
    throw std::runtime_error("film state: its spectral buckets are not this film's");
  track_buckets({count, range[0], range[1]});
  in.read(bucket_sum_.data(), bucket_sum_.size() * sizeof(FixedSum));
  if (has_splats) {
    bucket_splat_.assign(bucket_sum_.size(), FixedSum());
    in.read(bucket_splat_.data(), bucket_splat_.size() * sizeof(FixedSum));
  }
}

}  // namespace lantern
