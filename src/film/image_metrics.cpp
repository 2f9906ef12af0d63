#include "film/image_metrics.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

namespace lantern {

namespace {
void check_sizes(const Image& a, const Image& ref) {
  if (a.width != ref.width || a.height != ref.height)
    throw std::invalid_argument("image sizes differ: " + std::to_string(a.width) + "x" + std::to_string(a.height) +
                                " vs " + std::to_string(ref.width) + "x" + std::to_string(ref.height));
}
bool finite_pixel(const float* p) { return std::isfinite(p[0]) && std::isfinite(p[1]) && std::isfinite(p[2]); }

// blue -> green -> red as t goes from 0 to 1
void false_colour(float t, float* rgb) {
  rgb[0] = std::clamp(2.f * t - 1.f, 0.f, 1.f);
  rgb[1] = 1.f - std::fabs(2.f * t - 1.f);
  rgb[2] = std::clamp(1.f - 2.f * t, 0.f, 1.f);
}

// The mean of per-pixel errors but for the largest kRobustFraction of them.
double robust_mean(std::vector<double> errors, size_t& excluded) {
  if (errors.empty()) return 0.0;
  excluded = size_t(std::ceil(kRobustFraction * double(errors.size())));
  if (excluded >= errors.size()) excluded = 0;
  const size_t kept = errors.size() - excluded;
  std::nth_element(errors.begin(), errors.begin() + std::ptrdiff_t(kept), errors.end());
  double sum = 0.0;
  for (size_t i = 0; i < kept; ++i) sum += errors[i];
  return sum / double(kept);
}
}  // namespace

ImageComparison compare_images(const Image& a, const Image& ref) {
  check_sizes(a, ref);
  ImageComparison c;
  size_t n = 0;
  double peak = 0.0;
  std::vector<double> pixel_errors;  // relative squared error per pixel, for relmse_robust
  pixel_errors.reserve(size_t(a.width) * size_t(a.height));
  for (size_t i = 0; i < size_t(a.width) * size_t(a.height); ++i) {
    const float* pa = &a.rgb[3 * i];
    const float* pr = &ref.rgb[3 * i];
    if (!finite_pixel(pa) || !finite_pixel(pr)) {
      ++c.nonfinite;
      continue;
    }
    ++n;
    double pixel = 0.0;
    for (int k = 0; k < 3; ++k) {
      double d = double(pa[k]) - double(pr[k]);
      const double rel = d * d / (double(pr[k]) * double(pr[k]) + kRelMseEpsilon);
      c.mse += d * d;
      c.relmse += rel;
      pixel += rel / 3.0;
      c.mae += std::fabs(d);
      c.mean_a[size_t(k)] += pa[k];
      c.mean_ref[size_t(k)] += pr[k];
      c.pbrt_mse[size_t(k)] += d * d;
      c.pbrt_mrse[size_t(k)] += d * d / ((double(pr[k]) + 0.01) * (double(pr[k]) + 0.01));
      peak = std::max(peak, double(pr[k]));
    }
    pixel_errors.push_back(pixel);
  }
  if (n == 0) return c;
  double inv = 1.0 / double(3 * n);
  c.mse *= inv;
  c.relmse *= inv;
  c.mae *= inv;
  c.psnr = c.mse > 0 ? (peak > 0 ? 10.0 * std::log10(peak * peak / c.mse) : -INFINITY) : INFINITY;
  c.relmse_robust = robust_mean(std::move(pixel_errors), c.robust_excluded);
  for (size_t k = 0; k < 3; ++k) {
    c.pbrt_mse[k] /= double(n);
    c.pbrt_mrse[k] /= double(n);
    c.mean_a[k] /= double(n);
    c.mean_ref[k] /= double(n);
    c.ratio[k] = c.mean_ref[k] != 0.0 ? c.mean_a[k] / c.mean_ref[k] : 0.0;
  }
  return c;
}

Image relative_error_image(const Image& a, const Image& ref, double scale, bool legend) {
  check_sizes(a, ref);
  Image out;
  out.width = a.width;
  const int bar = legend ? std::max(4, a.height / 10) : 0;
  out.height = a.height + bar;
  out.rgb.resize(size_t(out.width) * size_t(out.height) * 3);
  for (size_t i = 0; i < size_t(a.width) * size_t(a.height); ++i) {
    double e = 0.0;
    for (size_t k = 0; k < 3; ++k) {
      double d = double(a.rgb[3 * i + k]) - double(ref.rgb[3 * i + k]);
      e += d * d / (double(ref.rgb[3 * i + k]) * double(ref.rgb[3 * i + k]) + kRelMseEpsilon) / 3.0;
    }
    // blue -> green -> red as the error grows towards `scale`
    false_colour(std::isfinite(e) ? float(std::clamp(e / scale, 0.0, 1.0)) : 1.f, &out.rgb[3 * i]);
  }
  for (int y = a.height; y < out.height; ++y)  // the legend: 0 at the left, scale at the right
    for (int x = 0; x < out.width; ++x) false_colour(out.width > 1 ? float(x) / float(out.width - 1) : 0.f, out.at(x, y));
  return out;
}

}  // namespace lantern
