#include "integrator/adaptive_sampling.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include "film/image_metrics.h"

namespace lantern {

namespace {

double mean_squared(const Film::Halves& h) { return halves_mean_squared(h.even, h.odd, h.value); }

}  // namespace

double estimated_error(const Film& film, const uint32_t* pixels, size_t n, ErrorMeasure measure) {
  if (n == 0 || film.sample_count(pixels[0]) < 2) return 0.0;
  double e = 0.0;
  for (size_t i = 0; i < n; ++i)
    for (int c = 0; c < 3; ++c) {
      const Film::Halves h = film.halves(pixels[i], c);
      const double scale = mean_squared(h) + kRelMseEpsilon;
      e += (h.even - h.odd) * (h.even - h.odd) / 4.0 / (measure == ErrorMeasure::Relative ? scale : std::sqrt(scale));
    }
  return e / (3.0 * double(n));
}

double estimated_relmse(const Film& film, const uint32_t* pixels, size_t n) {
  return estimated_error(film, pixels, n, ErrorMeasure::Relative);
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

PassSummary summarize_budget_pass(const Film& film, const std::vector<uint32_t>& order, uint32_t pixels_per_wave,
                                  uint32_t s) {
  std::vector<std::pair<double, size_t>> roots;  // sqrt(v_b), pixels
  double error = 0.0;
  size_t pixels = 0;
  for_each_block(order, pixels_per_wave, [&](const uint32_t* block, size_t n) {
    error += estimated_relmse(film, block, n) * double(n);
    pixels += n;
    const double e = estimated_error(film, block, n, ErrorMeasure::Balanced);
    roots.emplace_back(std::sqrt(e * double(film.sample_count(block[0]))), n);
  });
  PassSummary m;
  if (pixels == 0) return m;
  m.estimate = error / double(pixels);
  std::sort(roots.begin(), roots.end());
  double R = roots.back().first;
  size_t below = 0;
  for (const auto& [root, n] : roots)
    if (double(below += n) >= kAdaptiveRateQuantile * double(pixels)) {
      R = root;
      break;
    }
  m.lambda = R > 0.0 ? (R / double(s)) * (R / double(s)) : 0.0;
  return m;
}

void decide_pass(Film& film, const std::vector<uint32_t>& order, uint32_t pixels_per_wave, double lambda, uint32_t pass,
                 uint32_t underway_spp, ErrorMeasure measure) {
  uint8_t* mask = film.pass_mask(pass);
  for_each_block(order, pixels_per_wave, [&](const uint32_t* pixels, size_t n) {
    // A block's pixels have taken the same passes, so the same count.
    const uint32_t count = film.sample_count(pixels[0]);
    // (the pass under way, which it may be taking, counted as taken)
    const bool needed = count + underway_spp < kAdaptiveFirstSamples ||
                        estimated_error(film, pixels, n, measure) > lambda * double(count);
    for (size_t i = 0; i < n; ++i) mask[pixels[i]] = needed ? 1 : 0;
  });
}

void trim_pass(Film& film, const std::vector<uint32_t>& order, uint32_t pixels_per_wave, uint32_t pass, uint64_t pixels,
               ErrorMeasure measure) {
  uint8_t* mask = film.pass_mask(pass);
  struct Block {
    double need;
    const uint32_t* pixels;
    size_t n;
  };
  std::vector<Block> taking;
  uint64_t total = 0;
  for_each_block(order, pixels_per_wave, [&](const uint32_t* block, size_t n) {
    if (!mask[block[0]]) return;
    const double count = std::max(1.0, double(film.sample_count(block[0])));
    taking.push_back({estimated_error(film, block, n, measure) / count, block, n});
    total += n;
  });
  if (total <= pixels) return;
  // Stable: equal needs keep the tile order, so the choice is the same
  // wherever it is made.
  std::stable_sort(taking.begin(), taking.end(), [](const Block& a, const Block& b) { return a.need > b.need; });
  uint64_t kept = 0;
  for (const Block& b : taking) {
    const bool keep = kept + b.n <= pixels;
    if (keep) kept += b.n;
    for (size_t i = 0; i < b.n; ++i) mask[b.pixels[i]] = keep ? 1 : 0;
  }
}

uint64_t pixels_taking(const Film& film, uint32_t pass) {
  const size_t n = size_t(film.width()) * size_t(film.height());
  if (pass < 2) return n;
  const uint8_t* mask = film.pass_mask(pass);
  return uint64_t(std::count(mask, mask + n, uint8_t(1)));
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

AdaptiveGoal adaptive_goal(const RenderOptions& opt, size_t pixels) {
  AdaptiveGoal g;
  if (opt.target_error > 0) g.target = opt.target_error;
  else if (opt.adaptive)
    g.budget = opt.time_limit_seconds > 0 ? std::numeric_limits<double>::infinity() : double(opt.spp) * double(pixels);
  return g;
}

AdaptivePasses::AdaptivePasses(Film& film, std::mutex& film_mutex, const std::vector<uint32_t>& order,
                               uint32_t pixels_per_wave, uint32_t pass_spp, AdaptiveGoal goal)
    : film_(film), mutex_(film_mutex), order_(order), pixels_per_wave_(pixels_per_wave), pass_spp_(pass_spp),
      goal_(goal) {
  if (on()) film_.track_halves();
}

void AdaptivePasses::relayout(uint32_t from, uint32_t pass_spp) {
  from_ = from;
  after_spp_ = pass_spp;
}

uint32_t AdaptivePasses::first_of(uint32_t pass) const {
  const uint32_t before = from_ / pass_spp_;  // the passes before the relayout
  return pass < before ? pass * pass_spp_ : from_ + (pass - before) * after_spp_;
}

bool AdaptivePasses::reached(uint32_t pass) const {
  if (!on() || pass < 2) return false;
  std::lock_guard<std::mutex> lock(mutex_);
  const std::vector<double>& measured = film_.pass_measurements();
  const double lambda = measured.at(2 * size_t(pass - 2)), estimate = measured.at(2 * size_t(pass - 2) + 1);
  return std::isinf(lambda) || (goal_.target > 0 && estimate < goal_.target);
}

void AdaptivePasses::measure_before(uint32_t pass) {
  if (!on() || pass == 0) return;
  std::lock_guard<std::mutex> lock(mutex_);
  std::vector<double>& measured = film_.pass_measurements();
  if (measured.size() >= 2 * size_t(pass)) return;
  PassSummary m = goal_.target > 0 ? summarize_pass(film_, order_, pixels_per_wave_, goal_.target)
                                   : summarize_budget_pass(film_, order_, pixels_per_wave_, first_of(pass + 1));
  decide_pass(film_, order_, pixels_per_wave_, m.lambda, pass + 1, spp_of(pass), goal_.measure());
  if (goal_.target <= 0 && pixels_taking(film_, pass + 1) == 0) {
    // No block's estimate asks for more (an image without light, or one
    // converged to the estimate's precision): a budget is spent evenly
    // rather than on passes that render nothing.
    std::fill_n(film_.pass_mask(pass + 1), order_.size(), uint8_t(1));
  }
  if (goal_.target <= 0 && std::isfinite(goal_.budget)) {
    // The samples the image holds once pass `pass` is merged; what is left
    // goes to pass + 1, and none after it.
    const double planned = double(film_.total_samples()) + double(spp_of(pass)) * double(pixels_taking(film_, pass));
    const double left = std::floor((goal_.budget - planned) / double(spp_of(pass + 1)));
    if (left >= 1.0) trim_pass(film_, order_, pixels_per_wave_, pass + 1, uint64_t(left), goal_.measure());
    // Spent, to a block: no block that asks fits in what is left. (Passes
    // of different sizes, pairs of one sample before a guided render's
    // relayout, leave remainders no block of a larger pass fits; nor may
    // a partial block at a wave's end, where the others are whole.)
    if (left < 1.0 || pixels_taking(film_, pass + 1) == 0) {
      m.lambda = std::numeric_limits<double>::infinity();
      std::fill_n(film_.pass_mask(pass + 1), order_.size(), uint8_t(0));
    }
  }
  measured.push_back(m.lambda);
  measured.push_back(m.estimate);
}

void AdaptivePasses::choose(uint32_t pass, const uint32_t* pixels, size_t n, std::vector<uint32_t>& active) const {
  active.clear();
  append_active_pixels(film_, pass, pixels, n, active);
}

}  // namespace lantern
