// Region means and their standard errors, the figures the conformance suite
// compares (tests/conformance/README.md). Each renderer renders the scene
// twice with different seeds: a region's mean is over both images, and its
// standard error comes from the pixels' differences between them, so that
// it measures the estimator's noise alone and not the image's own detail
// (pixels taken as independent): with m_i = (a_i + b_i) / 2 the region mean
// M = sum m_i / n has var(M) = sum var(m_i) / n^2 and var(m_i) =
// E[(a_i - b_i)^2] / 4.
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

inline RegionStats region_stats(const Image& a, const Image& b, Box box) {
  if (a.width != b.width || a.height != b.height)
    throw std::runtime_error("the two renders differ in size: " + std::to_string(a.width) + "x" +
                             std::to_string(a.height) + " and " + std::to_string(b.width) + "x" + std::to_string(b.height));
  if (box.x0 < 0 || box.y0 < 0 || box.x1 > a.width || box.y1 > a.height || box.x1 <= box.x0 || box.y1 <= box.y0)
    throw std::runtime_error("region [" + std::to_string(box.x0) + " " + std::to_string(box.y0) + " " +
                             std::to_string(box.x1) + " " + std::to_string(box.y1) + "] does not fit the " +
                             std::to_string(a.width) + "x" + std::to_string(a.height) + " image");
  RegionStats s;
  const double n = double(box.x1 - box.x0) * double(box.y1 - box.y0);
  for (int c = 0; c < 3; ++c) {
    double sum = 0.0, diff2 = 0.0;
    for (int y = box.y0; y < box.y1; ++y)
      for (int x = box.x0; x < box.x1; ++x) {
        const double va = a.at(x, y)[c], vb = b.at(x, y)[c];
        sum += 0.5 * (va + vb);
        diff2 += (va - vb) * (va - vb);
      }
    s.mean[c] = sum / n;
    s.stderr_[c] = std::sqrt(diff2) / (2.0 * n);
  }
  return s;
}

}  // namespace lantern::conformance
