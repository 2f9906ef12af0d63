// Adaptive sampling (--target-error, --adaptive): each pixel's error
// estimated from its own samples, and samples spent only where the
// estimate is above the target, or where they pay the most.
//
// The estimate compares two halves of a pixel's samples, "even" and "odd"
// (each half of a pass's sample indices: halves_bit in wave.h), the film
// summing the odd camera samples, the odd
// light paths' splats and their count apart (Film::track_halves), so that
// it can give a pixel's value from each half alone. With A and B those
// and I the pixel, A - B has four times the variance of I, so
//   Var(I) ~ (A - B)^2 / 4,
// an unbiased estimate from one pixel, however its samples are
// distributed (Rousselle et al. 2012 and Cycles use the same two
// half-buffers). The relative MSE divides it by the pixel's mean squared
// plus 0.01, as the image metrics do (film/image_metrics.h) with the
// reference's value, which is not known here: estimated by A B, not below
// (0.7 I)^2. I^2 itself would hide part of the error of rare bright samples
// (caustics found by light tracing, a lamp seen through a gap), which
// raise it with the numerator: the estimate was half the measured error
// there (docs/adaptive-sampling.md). Correlated samples (the
// low-discrepancy samplers) make the estimate high: each half converges
// more slowly than the whole does.
//
// Which pixels take samples: to reach an image relMSE of E with the
// fewest samples, a block b of per-sample relative variance v_b should
// take n_b proportional to sqrt(v_b) (minimise sum n_b subject to
// mean v_b / n_b = E), where its error e_b = v_b / n_b over n_b is the
// same for all blocks: lambda = (E / mean sqrt(v_b))^2. So a block takes a
// pass while e_b > lambda n_b.
//
// One pixel's estimate is noisy (a few degrees of freedom), so pixels are
// decided in blocks: kAdaptiveBlock consecutive pixels of the tile order
// (a row of a 16x16 tile), inside one wave. The decisions are taken for
// the whole image at the end of a pass, where the film holds exactly the
// passes so far (splats of every wave included), for the pass after next
// (the next one's waves may already be running): they do not depend on the
// thread count or the scheduling, and the film keeps them for a resume.
// Every block takes passes until it has kAdaptiveFirstSamples (two passes
// of 16 samples, or sixteen pairs of one). The render stops before pass p
// when the image estimate at the end of pass p - 2 is below E.
//
// Without a target (--adaptive), the render has a budget instead: a mean
// number of samples per pixel, or a time. The same allocation, n_b
// proportional to sqrt(v_b) with v_b in the balanced measure (ErrorMeasure
// below), is then followed for a total that grows pass by pass: deciding
// pass p + 1, a block takes it while
//   n_b < s sqrt(v_b) / R,   s the samples before pass p + 1,
// R the 95th percentile of sqrt(v_b) over the image's pixels. So the
// blocks at R and above take every pass (one pass is the most a block can
// take at a time), and a block of a quarter of R's root variance every
// fourth; lambda = (R / s)^2 in the test above. A pass no block asks for
// (no light) is taken by all. A sample budget is
// spent exactly, to a block: when the pass after next would pass it, that
// pass keeps the blocks of largest e_b / n_b that fit, and the render
// ends after it (lambda recorded as infinity); so too when none of the
// blocks that ask fits in what is left.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <mutex>
#include <vector>

#include "film/film.h"
#include "lantern/render.h"

namespace lantern {

inline constexpr uint32_t kAdaptiveFirstSamples = 32;
inline constexpr uint32_t kAdaptiveBlock = 16;
// A budget's per-pixel limit.
inline constexpr uint32_t kAdaptiveMaxSpp = 1u << 16;
// Which quantile of the blocks' root variances takes every pass.
inline constexpr double kAdaptiveRateQuantile = 0.95;
// The least a pixel's mean is taken to be, as a share of its value, where
// one half's mean times the other's is less (estimated_error): chosen by
// measurement (docs/adaptive-sampling.md, "The estimate"): 0.5 left the
// Cornell box's estimate 2.1 times its measured error, 1 (the value
// squared) the lamp street's 0.42 times.
inline constexpr double kHalvesFloor = 0.7;
// A pixel's mean squared, which a relative error divides by, from the
// means of two independent halves of its samples, a and b, and of all of
// them, value: a times b (E[a b] = E[a] E[b], the mean squared), so that a
// rare bright sample in one half raises the squared difference (a - b)^2
// without raising this as much as it raises value^2, which correlates
// with it; not below (kHalvesFloor value)^2, where a half that found
// nothing would make it 0.
inline double halves_mean_squared(double a, double b, double value) {
  return std::max(a * b, kHalvesFloor * kHalvesFloor * value * value);
}

// What a block's error is measured in when blocks are chosen: its
// variance estimate (A - B)^2 / 4 over I^2 + 0.01 (Relative: relMSE's, what
// a target is), or over sqrt(I^2 + 0.01) (Balanced: a budget's, between
// MSE's weight 1 and relMSE's 1 / I^2, as Cycles normalises its error by
// sqrt(I)). Choosing by relMSE's own measure gives the bright pixels few
// samples, and their noise is much of the image's MSE: with a budget it
// left 1.1 times uniform sampling's MSE on the door ajar, where the
// balanced measure leaves 0.88 at the same relMSE, and on the street
// both measures fall (docs/adaptive-sampling.md, "Which error a budget
// lowers").
enum class ErrorMeasure : uint8_t { Relative, Balanced };

// What adaptive sampling aims at.
struct AdaptiveGoal {
  // > 0: stop once the image's estimated relMSE is below it.
  double target = 0.0;
  // > 0 without a target: the samples the image takes in all (a mean per
  // pixel times the pixels), or infinity when a time ends the render.
  double budget = 0.0;
  bool on() const { return target > 0 || budget > 0; }
  ErrorMeasure measure() const { return target > 0 ? ErrorMeasure::Relative : ErrorMeasure::Balanced; }
};

// A block's estimated error in `measure`, as below for relMSE.
double estimated_error(const Film& film, const uint32_t* pixels, size_t n, ErrorMeasure measure);

// The estimated relative MSE of the pixels[0, n) (a block, all with the
// same sample count; 0 below two), averaged over pixels and channels.
double estimated_relmse(const Film& film, const uint32_t* pixels, size_t n);

// Over the whole image: what --stats reports.
double estimated_image_relmse(const Film& film);

// At the end of a pass: the image's estimated relMSE, and lambda for a
// target E. `order` is the tile order, cut into waves of pixels_per_wave.
struct PassSummary {
  double estimate = 0.0, lambda = 0.0;
};
PassSummary summarize_pass(const Film& film, const std::vector<uint32_t>& order, uint32_t pixels_per_wave,
                           double target);
// Without a target: lambda for deciding a pass that begins at sample `s`
// (the rate rule above), in the summary's place.
PassSummary summarize_budget_pass(const Film& film, const std::vector<uint32_t>& order, uint32_t pixels_per_wave,
                                  uint32_t s);

// At the end of pass p - 2: which blocks take pass p under `lambda`
// (Film::pass_mask), pass p - 1, under way, being `underway_spp` samples.
void decide_pass(Film& film, const std::vector<uint32_t>& order, uint32_t pixels_per_wave, double lambda, uint32_t pass,
                 uint32_t underway_spp, ErrorMeasure measure);
// Keeps at most `pixels` of those that take pass p (p >= 2): whole blocks,
// those of largest e_b / n_b first (ties: tile order).
void trim_pass(Film& film, const std::vector<uint32_t>& order, uint32_t pixels_per_wave, uint32_t pass, uint64_t pixels,
               ErrorMeasure measure);
// The pixels that take pass p.
uint64_t pixels_taking(const Film& film, uint32_t pass);

// Appends to `active` the pixels of pixels[0, n) (a wave's) that take
// pass `pass` (all of them in the first two).
void append_active_pixels(const Film& film, uint32_t pass, const uint32_t* pixels, size_t n,
                          std::vector<uint32_t>& active);

// What `opt` asks for, over an image of `pixels` pixels.
AdaptiveGoal adaptive_goal(const RenderOptions& opt, size_t pixels);

// The render loop's side of it (integrator/run_passes.h): off,
// every pixel taking every pass, for a goal that is off.
class AdaptivePasses {
 public:
  // `order`: the tile order, cut into waves of pixels_per_wave (the blocks
  // lie inside them, and stay so after a relayout), of passes of pass_spp
  // samples; the film's
  // measurements and choices are read and written under film_mutex.
  AdaptivePasses(Film& film, std::mutex& film_mutex, const std::vector<uint32_t>& order, uint32_t pixels_per_wave,
                 uint32_t pass_spp, AdaptiveGoal goal);
  bool on() const { return goal_.on(); }
  // From sample `from` (a multiple of the passes' samples so far) on,
  // passes are `pass_spp` samples (a guided render's second layout,
  // integrator/pass_layout.h). Known before any pass from there on is
  // decided, and the same in every run of the render.
  void relayout(uint32_t from, uint32_t pass_spp);
  // The pass that holds sample `first`.
  uint32_t pass_of(uint32_t first) const {
    return first < from_ ? first / pass_spp_ : from_ / pass_spp_ + (first - from_) / after_spp_;
  }
  // Pass p is not to begin: the image estimate after pass p - 2 was below
  // the target, or the budget is spent.
  bool reached(uint32_t pass) const;
  // With the first wave of pass p, before it is merged (the film then holds
  // exactly the passes before p): measures pass p - 1 and chooses the
  // blocks of pass p + 1, unless a resumed render did before.
  void measure_before(uint32_t pass);
  // The pixels of pixels[0, n) (a wave's) that take pass p.
  void choose(uint32_t pass, const uint32_t* pixels, size_t n, std::vector<uint32_t>& active) const;

 private:
  Film& film_;
  std::mutex& mutex_;
  const std::vector<uint32_t>& order_;
  // The first sample of pass p, and its samples.
  uint32_t first_of(uint32_t pass) const;
  uint32_t spp_of(uint32_t pass) const { return first_of(pass + 1) - first_of(pass); }

  uint32_t pixels_per_wave_, pass_spp_;
  uint32_t from_ = UINT32_MAX, after_spp_ = 1;  // the passes from sample from_ on (relayout)
  AdaptiveGoal goal_;
};

}  // namespace lantern
