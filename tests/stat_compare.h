// Statistical comparison of estimators for the tests: the mean radiance of
// image regions over independent renders (different seeds), with standard
// errors, and the largest z statistic between two such estimates.
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <vector>

#include "lantern/render.h"
#include "lantern/scene.h"

namespace lantern {

struct Region {
  int x0, y0, w, h;
};

// Mean and standard error, over independent renders, of the mean radiance
// in each region and channel (of runs[r] - minus[r] when minus is given).
struct RegionStats {
  std::vector<std::array<double, 3>> mean, std_error;
};

inline RegionStats stats_of(const std::vector<Image>& runs, const std::vector<Region>& regions,
                     const std::vector<Image>* minus = nullptr) {
  const size_t n = runs.size();
  RegionStats st;
  st.mean.assign(regions.size(), {});
  st.std_error.assign(regions.size(), {});
  for (size_t g = 0; g < regions.size(); ++g)
    for (int c = 0; c < 3; ++c) {
      double sum = 0.0, sum2 = 0.0;
      for (size_t r = 0; r < n; ++r) {
        const Region& reg = regions[g];
        double v = 0.0;
        for (int y = reg.y0; y < reg.y0 + reg.h; ++y)
          for (int x = reg.x0; x < reg.x0 + reg.w; ++x)
            v += runs[r].at(x, y)[c] - (minus ? (*minus)[r].at(x, y)[c] : 0.f);
        v /= double(reg.w * reg.h);
        sum += v;
        sum2 += v * v;
      }
      double m = sum / double(n);
      st.mean[g][size_t(c)] = m;
      st.std_error[g][size_t(c)] = std::sqrt(std::max(0.0, (sum2 - double(n) * m * m) / double(n - 1)) / double(n));
    }
  return st;
}

// `runs` renders with seeds first_seed, first_seed + 1, ... The sanitizer
// suite (scripts/check-sanitized.sh) sets LANTERN_TEST_SPP_SCALE below 1:
// the same comparisons on fewer samples, whose standard errors widen with
// them, so the tolerances stay exact; the Release suite runs them in full.
inline std::vector<Image> render_runs(const Scene& scene, RenderOptions o, int runs, uint64_t first_seed) {
  // Not below 4 samples (or the test's own count, if smaller): with fewer,
  // a run's region means are too heavy-tailed for the z statistic.
  if (const char* scale = std::getenv("LANTERN_TEST_SPP_SCALE"))
    o.spp = std::max(std::min(o.spp, 4), int(std::lround(o.spp * std::atof(scale))));
  std::vector<Image> images;
  for (int r = 0; r < runs; ++r) {
    o.seed = first_seed + uint64_t(r);
    RenderResult res = render(scene, o);
    EXPECT_EQ(res.stats.nonfinite_samples, 0u);
    images.push_back(std::move(res.image));
  }
  return images;
}

// sampler: see BdptLightKinds for when a comparison wants "independent".
inline RegionStats render_stats(const Scene& scene, const std::string& integrator, int width, int height, int spp, int runs,
                         const std::vector<Region>& regions, bool unit_weights = false,
                         const std::string& sampler = "zsobol") {
  RenderOptions o;
  o.integrator = parse_integrator(integrator);
  o.sampler.type = parse_sampler(sampler);
  o.spp = spp;
  o.maxdepth = 6;
  o.width = width;
  o.height = height;
  o.debug_unit_mis_weights = unit_weights;
  return stats_of(render_runs(scene, o, runs, 1000), regions);
}

// Path-traced region means of `scene` (width x height, spp per run, `runs`
// independent runs) against values measured with pbrt-v4 (each test says
// how): every region and channel within 4 standard errors plus `allowance`
// (relative) of pbrt-v4's.
inline void expect_matches_pbrt(const Scene& scene, int width, int height, int maxdepth, int spp, int runs,
                                const std::vector<Region>& regions, const std::vector<std::array<double, 3>>& pbrt,
                                double allowance = 0.02, bool spectral = false) {
  RenderOptions o;
  o.spectral = spectral;
  o.integrator = Integrator::Path;
  o.spp = spp;
  o.maxdepth = maxdepth;
  o.width = width;
  o.height = height;
  const RegionStats st = stats_of(render_runs(scene, o, runs, 1000), regions);
  for (size_t g = 0; g < regions.size(); ++g)
    for (size_t c = 0; c < 3; ++c)
      EXPECT_LT(std::fabs(st.mean[g][c] - pbrt[g][c]), 4.0 * st.std_error[g][c] + allowance * pbrt[g][c])
          << "region " << g << " channel " << c << ": " << st.mean[g][c] << " against pbrt-v4's " << pbrt[g][c];
}

// Two scenes that must render the same image bit for bit (the same random
// decisions on the same paths) with each integrator.
inline void expect_identical_renders(const Scene& a, const Scene& b, std::initializer_list<const char*> integrators,
                                     int spp = 4) {
  RenderOptions o;
  o.spp = spp;
  for (const char* integrator : integrators) {
    o.integrator = parse_integrator(integrator);
    EXPECT_EQ(render(a, o).image.rgb, render(b, o).image.rgb) << integrator;
  }
}

// The same image bit for bit on 1 and 2 threads, with each integrator.
inline void expect_thread_invariant(const Scene& scene, RenderOptions o, std::initializer_list<const char*> integrators) {
  for (const char* integrator : integrators) {
    o.integrator = parse_integrator(integrator);
    o.threads = 1;
    Image one = render(scene, o).image;
    o.threads = 2;
    EXPECT_EQ(one.rgb, render(scene, o).image.rgb) << integrator;
  }
}

// Largest |difference| / (combined standard error) over regions and channels.
inline double max_z_of(const RegionStats& a, const RegionStats& b) {
  double z = 0.0;
  for (size_t g = 0; g < a.mean.size(); ++g)
    for (size_t c = 0; c < 3; ++c) {
      double se = std::sqrt(a.std_error[g][c] * a.std_error[g][c] + b.std_error[g][c] * b.std_error[g][c]);
      double d = std::fabs(a.mean[g][c] - b.mean[g][c]);
      z = std::max(z, se > 0.0 ? d / se : (d > 1e-12 ? 1e9 : 0.0));
    }
  return z;
}
// Prints the statistic, so a log shows how much margin each check has.
#define max_z(a, b) print_z(#a " vs " #b, max_z_of(a, b))
inline double print_z(const char* what, double z) {
  std::printf("  z(%s) = %.2f\n", what, z);
  return z;
}

// The variance of one sample per pixel over independent renders of `spp`
// samples each, relative to the pixel's mean squared plus the image's
// mean squared (as the pilots of light_subpath_rate.h and
// eye_subpaths_alone.h measure), averaged over the image.
inline double relative_variance_of(const std::vector<Image>& images, int spp) {
  const Image& first = images[0];
  const double runs = double(images.size());
  auto value = [](const Image& im, int x, int y) {
    const float* p = im.at(x, y);
    return (double(p[0]) + double(p[1]) + double(p[2])) / 3.0;
  };
  double image = 0.0;
  for (const Image& im : images)
    for (int y = 0; y < first.height; ++y)
      for (int x = 0; x < first.width; ++x) image += value(im, x, y);
  image /= runs * first.width * first.height;
  double e = 0.0;
  for (int y = 0; y < first.height; ++y)
    for (int x = 0; x < first.width; ++x) {
      double sum = 0.0, sum2 = 0.0;
      for (const Image& im : images) {
        sum += value(im, x, y);
        sum2 += value(im, x, y) * value(im, x, y);
      }
      const double mean = sum / runs, var = (sum2 - runs * mean * mean) / (runs - 1.0);
      e += var * spp / (mean * mean + image * image);
    }
  return e / (double(first.width) * first.height);
}

// b's region means within 4.5 standard errors of the difference plus
// `allowance` (relative) of a's (a the reference: bdpt's, the path
// tracer's). (Means may be negative: colours outside sRGB's gamut.)
inline void expect_means_agree(const RegionStats& a, const RegionStats& b, double allowance, const char* what) {
  for (size_t g = 0; g < a.mean.size(); ++g)
    for (size_t c = 0; c < 3; ++c) {
      const double se = std::hypot(a.std_error[g][c], b.std_error[g][c]);
      EXPECT_LE(std::fabs(b.mean[g][c] - a.mean[g][c]), 4.5 * se + allowance * std::fabs(a.mean[g][c]))
          << what << ", region " << g << " channel " << c << ": " << b.mean[g][c] << " against " << a.mean[g][c];
    }
}

}  // namespace lantern
