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
};

inline constexpr double kRelMseEpsilon = 1e-2;

// Throws std::invalid_argument when the sizes differ.
ImageComparison compare_images(const Image& a, const Image& ref);

// A false-colour map of the per-pixel relative squared error (blue = 0,
// red = at or above `scale`), for looking at where two images disagree.
Image relative_error_image(const Image& a, const Image& ref, double scale);

}  // namespace lantern
