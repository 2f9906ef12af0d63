#include "film/image_metrics.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace lantern {

namespace {
void check_sizes(const Image& a, const Image& ref) {
  if (a.width != ref.width || a.height != ref.height)
    throw std::invalid_argument("image sizes differ: " + std::to_string(a.width) + "x" + std::to_string(a.height) +
                                " vs " + std::to_string(ref.width) + "x" + std::to_string(ref.height));
}
bool finite_pixel(const float* p) { return std::isfinite(p[0]) && std::isfinite(p[1]) && std::isfinite(p[2]); }
}  // namespace

ImageComparison compare_images(const Image& a, const Image& ref) {
  check_sizes(a, ref);
  ImageComparison c;
  size_t n = 0;
  for (size_t i = 0; i < size_t(a.width) * size_t(a.height); ++i) {
    const float* pa = &a.rgb[3 * i];
    const float* pr = &ref.rgb[3 * i];
    if (!finite_pixel(pa) || !finite_pixel(pr)) {
      ++c.nonfinite;
      continue;
    }
    ++n;
    for (int k = 0; k < 3; ++k) {
      double d = double(pa[k]) - double(pr[k]);
      c.mse += d * d;
      c.relmse += d * d / (double(pr[k]) * double(pr[k]) + kRelMseEpsilon);
      c.mae += std::fabs(d);
      c.mean_a[size_t(k)] += pa[k];
      c.mean_ref[size_t(k)] += pr[k];
    }
  }
  if (n == 0) return c;
  double inv = 1.0 / double(3 * n);
  c.mse *= inv;
  c.relmse *= inv;
  c.mae *= inv;
  for (size_t k = 0; k < 3; ++k) {
    c.mean_a[k] /= double(n);
    c.mean_ref[k] /= double(n);
    c.ratio[k] = c.mean_ref[k] != 0.0 ? c.mean_a[k] / c.mean_ref[k] : 0.0;
  }
  return c;
}

Image relative_error_image(const Image& a, const Image& ref, double scale) {
  check_sizes(a, ref);
  Image out;
  out.width = a.width;
  out.height = a.height;
  out.rgb.resize(a.rgb.size());
  for (size_t i = 0; i < size_t(a.width) * size_t(a.height); ++i) {
    double e = 0.0;
    for (size_t k = 0; k < 3; ++k) {
      double d = double(a.rgb[3 * i + k]) - double(ref.rgb[3 * i + k]);
      e += d * d / (double(ref.rgb[3 * i + k]) * double(ref.rgb[3 * i + k]) + kRelMseEpsilon) / 3.0;
    }
    // blue -> green -> red as the error grows towards `scale`
    float t = std::isfinite(e) ? float(std::clamp(e / scale, 0.0, 1.0)) : 1.f;
    out.rgb[3 * i + 0] = std::clamp(2.f * t - 1.f, 0.f, 1.f);
    out.rgb[3 * i + 1] = 1.f - std::fabs(2.f * t - 1.f);
    out.rgb[3 * i + 2] = std::clamp(1.f - 2.f * t, 0.f, 1.f);
  }
  return out;
}

}  // namespace lantern
