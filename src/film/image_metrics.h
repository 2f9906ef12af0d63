// Error metrics between an image and a reference, for tests, benchmarks and
// `lantern compare`.
#pragma once

#include <array>

#include "lantern/image.h"

namespace lantern {

struct ImageComparison {
  double mse = 0.0;
  // Mean over pixels and channels of (a - r)^2 / (r^2 + eps), eps = 1e-2: the
  // relative MSE of Rousselle et al. 2011, as pbrt's tools report it.
  double relmse = 0.0;
  double mae = 0.0;
  std::array<double, 3> mean_a{}, mean_ref{};
  std::array<double, 3> ratio{};  // mean_a / mean_ref per channel
  size_t nonfinite = 0;           // pixels with a NaN or Inf channel (left out of the means)
  // 10 log10(peak^2 / mse), peak the reference's largest finite channel
  // value; infinite for identical images.
  double psnr = 0.0;
  // pbrt-v4's definitions (its Image::MSE and Image::MRSE, which imgtool
  // prints), per channel: the mean over pixels of (a - r)^2, and of
  // (a - r)^2 / (r + 0.01)^2.
  std::array<double, 3> pbrt_mse{}, pbrt_mrse{};
  // relmse without the pixels whose relative squared error (the mean of
  // their channels') is in the top kRobustFraction of all: a few fireflies
  // can make up most of a relmse, and this says what the rest of the image
  // looks like. robust_excluded: how many pixels that left out.
  double relmse_robust = 0.0;
  size_t robust_excluded = 0;
};

inline constexpr double kRobustFraction = 1e-4;  // 0.01% of the pixels

inline constexpr double kRelMseEpsilon = 1e-2;

// Throws std::invalid_argument when the sizes differ.
ImageComparison compare_images(const Image& a, const Image& ref);

// A false-colour map of the per-pixel relative squared error (blue = 0,
// red = at or above `scale`), for looking at where two images disagree.
// With legend: a bar below the image, a tenth of its height (at least 4
// rows), from 0 at the left to `scale` at the right, in the same colours.
Image relative_error_image(const Image& a, const Image& ref, double scale, bool legend = false);

}  // namespace lantern
