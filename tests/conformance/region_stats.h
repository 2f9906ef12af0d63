// Region means and their standard errors, the figures the conformance suite
// compares (tests/conformance/README.md). The standard error comes from the
// spread of the region's pixels: each pixel is an independent estimate, and
// the suite's regions are chosen flat, so the spread is the estimator's
// noise (on a region that is not flat it overstates the error).
#pragma once

#include <cmath>
#include <stdexcept>
#include <string>

#include "lantern/image.h"

namespace lantern::conformance {

struct Box {
  int x0 = 0, y0 = 0, x1 = 0, y1 = 0;  // pixels [x0, x1) x [y0, y1), row 0 at the top
};

struct RegionStats {
  double mean[3] = {0, 0, 0};
  double stderr_[3] = {0, 0, 0};
};

inline RegionStats region_stats(const Image& image, Box b) {
  if (b.x0 < 0 || b.y0 < 0 || b.x1 > image.width || b.y1 > image.height || b.x1 - b.x0 < 2 || b.y1 - b.y0 < 1)
    throw std::runtime_error("region [" + std::to_string(b.x0) + " " + std::to_string(b.y0) + " " +
                             std::to_string(b.x1) + " " + std::to_string(b.y1) + "] does not fit the " +
                             std::to_string(image.width) + "x" + std::to_string(image.height) + " image");
  RegionStats s;
  const double n = double(b.x1 - b.x0) * double(b.y1 - b.y0);
  for (int c = 0; c < 3; ++c) {
    double sum = 0.0, sum2 = 0.0;
    for (int y = b.y0; y < b.y1; ++y)
      for (int x = b.x0; x < b.x1; ++x) {
        const double v = image.at(x, y)[c];
        sum += v;
        sum2 += v * v;
      }
    s.mean[c] = sum / n;
    const double var = std::fmax(0.0, (sum2 - sum * sum / n) / (n - 1.0));
    s.stderr_[c] = std::sqrt(var / n);
  }
  return s;
}

}  // namespace lantern::conformance
