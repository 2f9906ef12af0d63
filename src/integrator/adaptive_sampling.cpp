#include "integrator/adaptive_sampling.h"

#include <algorithm>
#include <cmath>

#include "film/image_metrics.h"

namespace lantern {

double estimated_relmse(const Film& film, const uint32_t* pixels, size_t n) {
  if (n == 0 || film.sample_count(pixels[0]) < 2) return 0.0;
  double e = 0.0;
  for (size_t i = 0; i < n; ++i)
    for (int c = 0; c < 3; ++c) {
      const Film::Halves h = film.halves(pixels[i], c);
      e += (h.even - h.odd) * (h.even - h.odd) / 4.0 / (h.value * h.value + kRelMseEpsilon);
    }
  return e / (3.0 * double(n));
}

double estimated_image_relmse(const Film& film) {
  const size_t n = size_t(film.width()) * size_t(film.height());
  double e = 0.0;
  for (uint32_t p = 0; p < n; ++p) e += estimated_relmse(film, &p, 1);
  return n ? e / double(n) : 0.0;
}

namespace {

// Calls fn(first pixel, count) for each block of the waves.
template <class Fn>
void for_each_block(const std::vector<uint32_t>& order, uint32_t pixels_per_wave, Fn&& fn) {
  for (size_t w = 0; w < order.size(); w += pixels_per_wave) {
    const size_t end = std::min<size_t>(order.size(), w + pixels_per_wave);
    for (size_t b = w; b < end; b += kAdaptiveBlock) fn(order.data() + b, std::min<size_t>(kAdaptiveBlock, end - b));
  }
}

}  // namespace

PassSummary summarize_pass(const Film& film, const std::vector<uint32_t>& order, uint32_t pixels_per_wave,
                           double target) {
  double error = 0.0, root = 0.0;  // sums over pixels of e_b and of sqrt(v_b)
  for_each_block(order, pixels_per_wave, [&](const uint32_t* pixels, size_t n) {
    const double e = estimated_relmse(film, pixels, n);
    error += e * double(n);
    root += std::sqrt(e * double(film.sample_count(pixels[0]))) * double(n);
  });
  PassSummary s;
  if (order.empty()) return s;
  s.estimate = error / double(order.size());
  const double mean_root = root / double(order.size());
  s.lambda = mean_root > 0.0 ? (target / mean_root) * (target / mean_root) : 0.0;
  return s;
}

void decide_pass(Film& film, const std::vector<uint32_t>& order, uint32_t pixels_per_wave, double lambda,
                 uint32_t pass) {
  uint8_t* mask = film.pass_mask(pass);
  for_each_block(order, pixels_per_wave, [&](const uint32_t* pixels, size_t n) {
    // A block's pixels have taken the same passes, so the same count.
    const uint32_t count = film.sample_count(pixels[0]);
    const bool needed = count < kAdaptiveMinSamples || estimated_relmse(film, pixels, n) > lambda * double(count);
    for (size_t i = 0; i < n; ++i) mask[pixels[i]] = needed ? 1 : 0;
  });
}

void append_active_pixels(const Film& film, uint32_t pass, const uint32_t* pixels, size_t n,
                          std::vector<uint32_t>& active) {
  if (pass < 2) {
    active.assign(pixels, pixels + n);
    return;
  }
  const uint8_t* mask = film.pass_mask(pass);
  for (size_t i = 0; i < n; ++i)
    if (mask[pixels[i]]) active.push_back(pixels[i]);
}

AdaptivePasses::AdaptivePasses(Film& film, std::mutex& film_mutex, const std::vector<uint32_t>& order,
                               uint32_t pixels_per_wave, double target)
    : film_(film), mutex_(film_mutex), order_(order), pixels_per_wave_(pixels_per_wave), target_(target) {
  if (on()) film_.track_halves();
}

bool AdaptivePasses::reached(uint32_t pass) const {
  if (!on() || pass < 2) return false;
  std::lock_guard<std::mutex> lock(mutex_);
  return film_.pass_measurements().at(2 * size_t(pass - 2) + 1) < target_;
}

void AdaptivePasses::measure_before(uint32_t pass) {
  if (!on() || pass == 0) return;
  std::lock_guard<std::mutex> lock(mutex_);
  std::vector<double>& measured = film_.pass_measurements();
  if (measured.size() >= 2 * size_t(pass)) return;
  const PassSummary m = summarize_pass(film_, order_, pixels_per_wave_, target_);
  measured.push_back(m.lambda);
  measured.push_back(m.estimate);
  decide_pass(film_, order_, pixels_per_wave_, m.lambda, pass + 1);
}

void AdaptivePasses::choose(uint32_t pass, const uint32_t* pixels, size_t n, std::vector<uint32_t>& active) const {
  active.clear();
  append_active_pixels(film_, pass, pixels, n, active);
}

}  // namespace lantern
