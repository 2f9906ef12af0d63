// Null-collision tracking (medium/tracking.h) and the media tracked with
// it: delta and ratio tracking against the closed forms of a homogeneous
// medium, against each other and the exact integral of a heterogeneous
// grid, with coloured coefficients; then pbrt-v4's "cloud": the three
// integrators agree on it, and its image matches pbrt-v4's.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <random>
#include <string>

#include "expect_error.h"
#include "lantern/scene.h"
#include "medium/grid_density.h"
#include "medium/tracking.h"
#include "media_scenes.h"
#include "sanitizer.h"
#include "stat_compare.h"

namespace lantern {
namespace {

// Mean and standard error of the per-channel values of n runs.
struct ChannelMean {
  double sum[3] = {0, 0, 0}, sq[3] = {0, 0, 0};
  int n = 0;
  void add(const Spectrum& v) {
    for (int c = 0; c < 3; ++c) sum[c] += v[c], sq[c] += double(v[c]) * v[c];
    ++n;
  }
  double mean(int c) const { return sum[c] / n; }
  double se(int c) const { return std::sqrt(std::max(0.0, sq[c] / n - mean(c) * mean(c)) / n); }
  // |mean - expected| in standard errors (with a floor for exact estimators).
  double z(int c, double expected) const { return std::fabs(mean(c) - expected) / std::max(se(c), 1e-6); }
};

// A medium along one ray: sigma_t,c(t) = sigma_t,c rho(t), albedo per channel.
struct RayMedium {
  Spectrum sigma_t, albedo;
  std::function<float(float)> rho;  // the density along the ray
  std::function<float(float)> depth;  // its integral from 0
  void at(float t, Spectrum* a, Spectrum* s) const {
    const Spectrum st = sigma_t * rho(t);
    *s = st * albedo;
    *a = st - *s;
  }
  double T(int c, float t) const { return std::exp(-double(sigma_t[c]) * depth(t)); }
};

// Ratio tracking's mean is T; delta tracking passes with weight whose mean
// is T, and scatters before x with weight whose mean is the albedo times
// 1 - T(x) (the integral of sigma_s T), per channel.
void expect_tracking_matches(const RayMedium& m, float L, float sigma_bar, int runs) {
  ChannelMean ratio, pass, early, all;
  const float x = 0.4f * L;
  for (int i = 0; i < runs; ++i) {
    RandomStream rng = RandomStream::make(7, uint64_t(i), 0);
    ratio.add(tracking::ratio_track(L, sigma_bar, rng, [&](float t, Spectrum* a, Spectrum* s) { m.at(t, a, s); }));
    const tracking::Track tr =
        tracking::delta_track(L, sigma_bar, rng.get1d(), rng, [&](float t, Spectrum* a, Spectrum* s) { m.at(t, a, s); });
    ASSERT_FALSE(tr.saturated);
    pass.add(tr.real() ? Spectrum(0.f) : tr.weight);
    early.add(tr.real() && tr.t < x ? tr.weight : Spectrum(0.f));
    all.add(tr.real() ? tr.weight : Spectrum(0.f));
  }
  for (int c = 0; c < 3; ++c) {
    const double a = m.albedo[c];
    EXPECT_LT(ratio.z(c, m.T(c, L)), 4.5) << "ratio, channel " << c << ": " << ratio.mean(c) << " vs " << m.T(c, L);
    EXPECT_LT(pass.z(c, m.T(c, L)), 4.5) << "delta pass, channel " << c << ": " << pass.mean(c);
    EXPECT_LT(early.z(c, a * (1.0 - m.T(c, x))), 4.5) << "delta scatter before x, channel " << c << ": " << early.mean(c);
    EXPECT_LT(all.z(c, a * (1.0 - m.T(c, L))), 4.5) << "delta scatter, channel " << c << ": " << all.mean(c);
  }
}

TEST(Tracking, MatchesTheClosedFormsOfAHomogeneousMedium) {
  RayMedium m;
  m.sigma_t = Spectrum(1.f, 2.f, 0.5f, 2.f);
  m.albedo = Spectrum(0.9f, 0.5f, 1.f, 0.5f);
  m.rho = [](float) { return 1.f; };
  m.depth = [](float t) { return t; };
  expect_tracking_matches(m, 1.5f, 2.f, 40000);       // the majorant is the largest extinction
  expect_tracking_matches(m, 1.5f, 5.f, 40000);       // and far above it
  m.sigma_t = Spectrum(0.f, 1.f, 1.f, 1.f);                     // a channel that does not interact
  expect_tracking_matches(m, 1.5f, 1.f, 40000);
}

// A random trilinear grid along a ray through it: the exact integral from
// the lattice (medium/grid_density.h), tracked against its largest sample.
TEST(Tracking, AgreesWithTheExactIntegralOfAHeterogeneousGrid) {
  std::mt19937 gen(11);
  std::uniform_real_distribution<float> u(0.f, 1.f);
  DensityGrid g;
  g.nx = 5, g.ny = 4, g.nz = 3;
  float largest = 0.f;
  for (int i = 0; i < 60; ++i) {
    g.values.push_back(u(gen) < 0.3f ? 0.f : 2.f * u(gen));
    largest = std::max(largest, g.values.back());
  }
  const Vec3 o(-0.2f, 0.1f, 0.3f), d = glm::normalize(Vec3(1.f, 0.7f, 0.4f));
  RayMedium m;
  m.sigma_t = Spectrum(1.5f, 0.8f, 2.5f, 0.8f);
  m.albedo = Spectrum(0.8f, 1.f, 0.6f, 1.f);
  m.rho = [&](float t) { return g.density(o + d * t); };
  m.depth = [&](float t) {
    float unused;
    return g.integrate(o, d, 0.f, t, -1.f, &unused);
  };
  ASSERT_GT(m.depth(2.f), 0.3f);
  expect_tracking_matches(m, 2.f, largest * 2.5f, 40000);
}

TEST(Tracking, AnAbsurdMajorantEndsInBoundedTime) {
  RandomStream rng = RandomStream::make(1, 2, 3);
  auto none = [](float, Spectrum* a, Spectrum* s) { *a = *s = Spectrum(0.f); };
  const tracking::Track tr = tracking::delta_track(1e3f, 1e9f, 0.5f, rng, none);
  EXPECT_TRUE(tr.saturated);
  EXPECT_TRUE(is_black(tr.weight));
  EXPECT_TRUE(is_black(tracking::ratio_track(1e3f, 1e9f, rng, none)));
}

TEST(Cloud, IntegratorsAgree) {
  if (LANTERN_ASAN) GTEST_SKIP() << "the Release suite runs it";
  auto scene = load_scene(std::string(LANTERN_SOURCE_DIR) + "/perf/media/cloud.pbrt");
  const std::vector<Region> regions = {{13, 5, 14, 12}, {0, 0, 40, 30}, {12, 25, 10, 4}};
  expect_medium_integrators_agree(*scene, regions);
}

TEST(Cloud, ImagesDoNotDependOnThreads) {
  auto scene = load_scene(std::string(LANTERN_SOURCE_DIR) + "/perf/media/cloud.pbrt");
  expect_medium_thread_invariant(*scene);
}

// pbrt-v4 (a CPU Release build of its public source, volpath) rendered perf/media/cloud.pbrt at
// 160x120 with 512 spp; its means of the cloud (60x50 at 50,20), the whole
// image and the floor (40x15 at 50,100), by oiiotool --cut ... --printstats.
TEST(Cloud, MatchesPbrt) {
  if (LANTERN_ASAN) GTEST_SKIP() << "the Release suite runs it";
  auto scene = load_scene(std::string(LANTERN_SOURCE_DIR) + "/perf/media/cloud.pbrt");
  expect_matches_pbrt(*scene, 160, 120, 20, 16, 4, {{50, 20, 60, 50}, {0, 0, 160, 120}, {50, 100, 40, 15}},
                      {{0.145115, 0.134151, 0.118284}, {0.188478, 0.179942, 0.163948}, {0.402697, 0.385580, 0.352218}}, 0.01);
}

TEST(Cloud, BadParametersAreRefused) {
  const std::string head = "LookAt 0 0 0 0 0 1 0 1 0\nCamera \"perspective\"\nWorldBegin\n"
                           "MakeNamedMedium \"c\" \"string type\" \"cloud\" ";
  expect_load_error(head + "\"rgb sigma_s\" [ -1 1 1 ]\n", "a.pbrt", {"a.pbrt:4", "sigma_s", "must not be negative"});
  expect_load_error(head + "\"float g\" 1\n", "b.pbrt", {"b.pbrt:4", "strictly between -1 and 1"});
  expect_load_error(head + "\"point3 p0\" [ 0 2 0 ]\n", "c.pbrt", {"c.pbrt:4", "\"p0\" must lie below \"p1\""});
  expect_load_error(head + "\"float frequency\" 1e30\n", "d.pbrt", {"d.pbrt:4", "\"frequency\" must be finite"});
}

}  // namespace
}  // namespace lantern
