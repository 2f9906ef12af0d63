// Path guiding: the directional tree's sampling against its density
// (chi-square), its density's integral, the spatial tree's splits, and the
// guided path tracer against the unguided one (region means over seeds)
// and across thread counts (bit for bit).
#include <gtest/gtest.h>

#include <cstring>
#include <random>

#include "bsdf_checks.h"
#include "guiding/directional_tree.h"
#include "guiding/sd_tree.h"
#include "integrator/guided_scatter.h"
#include "integrator/guiding_field.h"
#include "lantern/error.h"
#include "lantern/render.h"
#include "lantern/scene.h"
#include "material/coated_diffuse_bsdf.h"
#include "material/diffuse_bsdf.h"
#include "math/equal_area.h"
#include "sanitizer.h"
#include "guided_rooms.h"
#include "stat_compare.h"

using namespace lantern;
using namespace lantern::guiding_test;

namespace {

// A tree learnt from energy deposited by a few lobes, refined twice and
// kept at most 6 levels deep, so that its density is constant on the
// 64 x 64 grid of the square the checks bin by.
DirectionalTree lobed_tree(double threshold) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> u(0.f, 1.f);
  DirectionalTree t;
  for (int round = 0; round < 3; ++round) {
    for (int i = 0; i < 20000; ++i) {
      Vec2 p(u(rng), u(rng));
      if (i % 3 == 0)
        p = Vec2(0.2f, 0.7f) + 0.1f * p;  // a lobe
      else if (i % 3 == 1)
        p = Vec2(0.6f, 0.1f) + 0.25f * p;
      t.add(t.cell_of(p), 1.0 + p.x);
    }
    t.sum_up();
    if (round < 2) t = t.refined(threshold);
  }
  return t;
}

constexpr int kGrid = 64;

// The cell of the 64 x 64 grid over the world's equal-area square that
// direction w falls in.
size_t grid_cell(const Vec3& w) {
  const Vec2 p = equal_area_sphere_to_square(w);
  return size_t(std::min(kGrid - 1, int(p.y * kGrid)) * kGrid + std::min(kGrid - 1, int(p.x * kGrid)));
}

// Chi-square of n directions binned in `observed` (grid_cell) against the
// solid-angle density `density(p)` at point p of the square: expected
// counts its integral over each cell, by 8 x 8 points (the guide's density
// is constant on a cell; the other factor smooth).
template <class Density>
void expect_directions_follow(const std::vector<double>& observed, int n, Density density, const std::string& what) {
  double chi2 = 0.0;
  int dof = 0;
  for (int by = 0; by < kGrid; ++by)
    for (int bx = 0; bx < kGrid; ++bx) {
      double e = 0.0;
      for (int sy = 0; sy < 8; ++sy)
        for (int sx = 0; sx < 8; ++sx) {
          const Vec2 p((bx + (sx + 0.5f) / 8.f) / kGrid, (by + (sy + 0.5f) / 8.f) / kGrid);
          e += density(p) * (4.0 * kPi / (kGrid * kGrid * 64.0));  // times the sphere's area per point
        }
      e *= n;
      if (e < 5.0) continue;
      chi2 += sqr(observed[size_t(by * kGrid + bx)] - e) / e;
      ++dof;
    }
  EXPECT_LT(chi2, bsdf_checks::chi2_critical(dof - 1)) << what;
}

// n directions drawn by draw(uc, u2) (a ScatterSample, or none): the mean
// of their estimates (none counting 0), its standard error, and their
// directions binned by grid_cell.
struct Draws {
  double mean = 0.0, se = 0.0;
  std::vector<double> observed = std::vector<double>(kGrid * kGrid, 0.0);
};
template <class Draw>
Draws draw_directions(int n, uint32_t seed, Draw draw) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(0.f, 1.f);
  Draws d;
  double sum = 0.0, sum2 = 0.0;
  for (int i = 0; i < n; ++i) {
    const float uc = u(rng);
    const Vec2 u2(u(rng), u(rng));
    const std::optional<ScatterSample> s = draw(uc, u2);
    if (!s) continue;
    const double w = s->weight[0];
    sum += w, sum2 += w * w;
    d.observed[grid_cell(s->wi)] += 1.0;
  }
  d.mean = sum / n;
  d.se = std::sqrt((sum2 / n - d.mean * d.mean) / n);
  return d;
}

}  // namespace

TEST(DirectionalTree, DensityIntegratesToOneAndMatchesItsSamples) {
  const DirectionalTree t = lobed_tree(0.02);
  ASSERT_LE(t.depth(), 6);
  ASSERT_GT(t.node_count(), 10u);
  std::vector<double> expected(kGrid * kGrid);
  double integral = 0.0;
  for (int y = 0; y < kGrid; ++y)
    for (int x = 0; x < kGrid; ++x) {
      const double p = t.pdf(Vec2((x + 0.5f) / kGrid, (y + 0.5f) / kGrid)) / double(kGrid * kGrid);
      expected[size_t(y * kGrid + x)] = p;
      integral += p;
    }
  EXPECT_NEAR(integral, 1.0, 1e-5);

  const int n = 400000;
  std::vector<double> observed(kGrid * kGrid, 0.0);
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> u(0.f, 1.f);
  int differing = 0;
  for (int i = 0; i < n; ++i) {
    float pdf = 0.f;
    const Vec2 p = t.sample(Vec2(u(rng), u(rng)), &pdf);
    ASSERT_TRUE(p.x >= 0.f && p.x <= 1.f && p.y >= 0.f && p.y <= 1.f);
    // The sample's density is the density at the point (but for points
    // that rounding moves across a cell's edge, with probability ~0).
    if (std::fabs(pdf - t.pdf(p)) > 1e-3f * pdf) ++differing;
    const int bx = std::min(kGrid - 1, int(p.x * kGrid)), by = std::min(kGrid - 1, int(p.y * kGrid));
    observed[size_t(by * kGrid + bx)] += 1.0;
  }
  EXPECT_LE(differing, 2);
  double chi2 = 0.0;
  int dof = 0;
  for (size_t b = 0; b < observed.size(); ++b) {
    const double e = expected[b] * n;
    if (e < 5.0) {
      EXPECT_EQ(observed[b], 0.0) << "a sample where the density is zero";
      continue;
    }
    chi2 += sqr(observed[b] - e) / e;
    ++dof;
  }
  EXPECT_LT(chi2, bsdf_checks::chi2_critical(dof - 1));
}

TEST(DirectionalTree, RefinesWhereEnergyIsAndCollapsesElsewhere) {
  DirectionalTree t;
  for (int i = 0; i < 100; ++i) t.add(t.cell_of(Vec2(0.9f, 0.9f)), 1.0);
  t.sum_up();
  const DirectionalTree r = t.refined(0.01);
  // All the energy in one quadrant of the root: split while a quadrant
  // holds more than 1%, the energy spread evenly inside the old leaf:
  // 100%, 25%, 6.25%, 1.56%, then 0.39% stays whole.
  EXPECT_EQ(r.depth(), 5);
  EXPECT_EQ(r.total(), 0.0) << "the refined tree starts without energy";
  // Energy spread evenly over four quadrants at 25% each: 6.25%, 1.56%,
  // then 0.39% stays whole.
  DirectionalTree even;
  for (float x : {0.25f, 0.75f})
    for (float y : {0.25f, 0.75f}) even.add(even.cell_of(Vec2(x, y)), 1.0);
  even.sum_up();
  EXPECT_EQ(even.refined(0.01).depth(), 4);
  // No energy: the structure stays.
  EXPECT_EQ(DirectionalTree().refined(0.01).node_count(), 1u);
}

TEST(DirectionalTree, EqualAreaSquareRoundTrips) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> u(0.f, 1.f);
  for (int i = 0; i < 1000; ++i) {
    const Vec2 p(u(rng), u(rng));
    const Vec2 q = equal_area_sphere_to_square(equal_area_square_to_sphere(p));
    EXPECT_NEAR(p.x, q.x, 1e-4f);
    EXPECT_NEAR(p.y, q.y, 1e-4f);
  }
}

TEST(SDTree, SplitsLeavesWithManyRecordsAndCopiesTheirDistribution) {
  SDTree tree(Vec3(0.f), Vec3(2.f, 1.f, 1.f), GuidingSettings{100.0, 0.01});
  const Vec3 a(0.2f, 0.5f, 0.5f), b(1.8f, 0.5f, 0.5f);
  EXPECT_EQ(tree.leaf_of(a), tree.leaf_of(b));
  const uint32_t leaf = tree.leaf_of(a);
  const uint32_t cell = tree.leaf(leaf).learning[2].cell_of(equal_area_square_to_sphere(Vec2(0.3f, 0.3f)));
  for (int i = 0; i < 1000; ++i) tree.add({leaf, cell, 1.f, 0.f, 0.f, -1.f, 2});
  tree.update(0);  // 1000 records over a limit of 100: split until each half holds at most 100
  EXPECT_TRUE(tree.trained());
  EXPECT_GE(tree.leaves().size(), 8u);
  EXPECT_NE(tree.leaf_of(a), tree.leaf_of(b));
  for (const SDTree::Leaf& l : tree.leaves()) {
    EXPECT_GT(l.sampled[2].total(), 0.0) << "every part starts from the parent's distribution";
    EXPECT_EQ(l.sampled[3].total(), 0.0) << "normals of other bins learn nothing from it";
    EXPECT_EQ(l.learning[2].total(), 0.0);
    EXPECT_EQ(l.records, 0u);
  }
  // A leaf with few records stays whole.
  SDTree quiet(Vec3(0.f), Vec3(1.f), GuidingSettings{100.0, 0.01});
  quiet.add({0, 0, 1.f, 0.f, 0.f, -1.f, 0});
  quiet.update(0);
  EXPECT_EQ(quiet.leaves().size(), 1u);
}

namespace {

// The mixture's sample estimates: their mean is the directional albedo
// (unbiased, whichever technique drew them), and their directions follow
// the mixture density the estimate divides by, where the BSDF is not zero
// (chi-square over the 64 x 64 grid of the world's equal-area square).
template <class BSDF>
void expect_mixture_sound(const BSDF& bsdf, double albedo, const std::string& what) {
  const GuideDistribution tree(lobed_tree(0.02));
  ASSERT_LE(tree.tree().depth(), 6);
  const GuideAt guide{&tree, 0.4f};
  const Frame frame = Frame::from_z(glm::normalize(Vec3(0.3f, 0.2f, 1.f)));
  const Vec3 wo = glm::normalize(Vec3(0.2f, -0.1f, 1.f));  // local
  const int n = 300000;
  const Draws d = draw_directions(n, 7, [&](float uc, Vec2 u2) {
    return sample_scatter(bsdf, frame, wo, guide, uc, u2, TransportMode::Radiance);
  });
  EXPECT_NEAR(d.mean, albedo, 4.0 * d.se + 1e-3 * albedo) << what << ": the estimates' mean is the albedo";
  expect_directions_follow(d.observed, n, [&](Vec2 p) {
    const Vec3 wi = frame.to_local(equal_area_square_to_sphere(p));
    // (the guide's directions where the BSDF is zero end the path: no sample)
    const bool reflects = bsdf.f(wo, wi, TransportMode::Radiance)[0] > 0.f;
    return reflects ? guide.mix(bsdf.pdf(wo, wi, TransportMode::Radiance), tree.tree().pdf(p) * kInv4Pi) : 0.f;
  }, what);
}

}  // namespace

// The BSDF's share follows the samples' second moments: a guide that
// matches the integrand where the BSDF does not takes most samples; one
// that puts its density where nothing is found gives them back.
TEST(SDTree, ChoosesTheBsdfShareWithTheLeastSecondMoment) {
  SDTree tree(Vec3(0.f), Vec3(1.f));
  const float alpha = SDTree::kFirstAlpha;
  // Bin 0: the integrand is a narrow lobe of density 20 that the guide has
  // (density 20 there) and the BSDF not (density 0.3); bin 1: the guide
  // spends its density elsewhere (0.1 on the lobe), the BSDF matches it.
  for (int i = 0; i < 2000; ++i) {
    // Directions on the lobe, drawn by the mixture with the first alpha:
    // F = f|cos|L / p_mix with f|cos|L = 20 (the integrand's density, up to a scale).
    const float p0 = alpha * 0.3f + (1.f - alpha) * 20.f;
    tree.add({0, 0, 0.f, 20.f * 20.f / p0, 0.3f, 20.f, 0});
    const float p1 = alpha * 20.f + (1.f - alpha) * 0.1f;
    tree.add({0, 0, 0.f, 20.f * 20.f / p1, 20.f, 0.1f, 1});
  }
  tree.update(0);
  EXPECT_EQ(tree.leaf(0).alpha[0], SDTree::kAlphas.front());
  EXPECT_EQ(tree.leaf(0).alpha[1], SDTree::kAlphas.back());
  EXPECT_EQ(tree.leaf(0).alpha[2], SDTree::kFirstAlpha) << "no records: the share stays";
}

TEST(GuidedScatter, DiffuseMixtureIsUnbiasedAndFollowsItsDensity) {
  expect_mixture_sound(DiffuseBSDF{Spectrum(0.6f)}, 0.6, "diffuse");
}

// The mixture at a medium vertex: the phase function integrates to one, so
// the estimates' mean is 1 whichever technique drew them, and directions
// follow the mixture density (chi-square over the equal-area square,
// whose cells are equal in solid angle). Forward, backward and isotropic
// scattering.
TEST(GuidedScatter, PhaseMixtureIsUnbiasedAndFollowsItsDensity) {
  const GuideDistribution tree(lobed_tree(0.02));
  ASSERT_LE(tree.tree().depth(), 6);
  const GuideAt guide{&tree, 0.3f};
  const Vec3 wo = glm::normalize(Vec3(0.4f, -0.3f, 0.8f));
  for (float g : {0.7f, -0.4f, 0.f}) {
    const HenyeyGreenstein phase{g};
    const int n = 200000;
    int drawn = 0, pdf_off = 0;
    const Draws d = draw_directions(n, 11, [&](float uc, Vec2 u2) {
      const auto s = sample_phase_scatter(phase, wo, guide, uc, u2);
      drawn += s.has_value();
      pdf_off += s && std::fabs(s->bsdf_pdf - phase.p(wo, s->wi)) > 1e-4f * s->bsdf_pdf;
      return s;
    });
    EXPECT_EQ(drawn, n) << "g " << g;
    EXPECT_EQ(pdf_off, 0) << "g " << g << ": the phase function's density is the one reported";
    EXPECT_NEAR(d.mean, 1.0, 4.0 * d.se + 1e-3) << "g " << g;
    expect_directions_follow(
        d.observed, n,
        [&](Vec2 p) { return guide.mix(phase.p(wo, equal_area_square_to_sphere(p)), tree.tree().pdf(p) * kInv4Pi); },
        "g " + std::to_string(g));
  }
}


// Guided paths converge to the unguided image: region means over
// independent runs agree within 4.5 standard errors.
TEST(Guiding, PathTracerConvergesToTheUnguidedImage) {
  const auto scene = guided_room();
  std::vector<Region> regions;
  for (int y = 0; y < 32; y += 8)
    for (int x = 0; x < 32; x += 8) regions.push_back({x, y, 8, 8});
  const RegionStats plain = stats_of(render_runs(*scene, guided_options(false), 6, 100), regions);
  const RegionStats guided = stats_of(render_runs(*scene, guided_options(true), 6, 200), regions);
  max_z(plain, guided);
  expect_means_agree(plain, guided, 0.0, "guided path");
}

// Guided eye subpaths in bdpt and vcm converge to the unguided image of the
// same integrator: their MIS weights keep the BSDF's densities, so only
// the throughput sees the mixture (integrator/shade.h). The sky seen
// through a hole in the ceiling makes the guide narrow: with the throughput
// divided by the BSDF's density instead of the mixture's, the guided means
// lie 7 standard errors off (checked). With vcm both images carry the same
// merging bias (the same radii).
TEST(Guiding, BdptAndVcmConvergeToTheirUnguidedImages) {
  // (Guided bdpt and vcm run under the sanitizers in SameImageOnOneAndTwoThreadsAndReportsItsField.)
  if (LANTERN_ASAN) GTEST_SKIP() << "statistics only: the Release suite runs it";
  const auto scene = skylit_room();
  std::vector<Region> regions;
  for (int y = 0; y < 32; y += 8)
    for (int x = 0; x < 32; x += 8) regions.push_back({x, y, 8, 8});
  for (Integrator integrator : {Integrator::Bdpt, Integrator::Vcm}) {
    RenderOptions plain_options = guided_options(false), guided = guided_options(true);
    plain_options.integrator = guided.integrator = integrator;
    plain_options.spp = guided.spp = 64;
    const RegionStats plain = stats_of(render_runs(*scene, plain_options, 8, 100), regions);
    const RegionStats with_guide = stats_of(render_runs(*scene, guided, 8, 200), regions);
    max_z(plain, with_guide);
    expect_means_agree(plain, with_guide, 0.0, integrator == Integrator::Bdpt ? "guided bdpt" : "guided vcm");
    // The guide was learnt and sampled: the same seed draws other paths.
    guided.seed = plain_options.seed = 5;
    guided.collect_stats = true;
    const RenderResult r = render(*scene, guided);
    EXPECT_GE(r.stats.guiding_iterations, 2u);
    EXPECT_NE(r.image.rgb, render(*scene, plain_options).image.rgb);
  }
}

// Paths that scatter in a medium draw their directions from the mixture
// of the phase function and the guide's medium distribution of their leaf,
// in the path tracer and on bdpt's eye subpaths: both converge to their
// unguided images. With the throughput divided by the phase function's
// density instead of the mixture's, the guided means lie 8.7 (path) and
// 6.0 (bdpt) standard errors off (checked).
TEST(Guiding, MediumVerticesConvergeToTheUnguidedImage) {
  if (LANTERN_ASAN) GTEST_SKIP() << "statistics only: the Release suite runs it";
  const auto scene = foggy_skylit_room();
  std::vector<Region> regions;
  for (int y = 0; y < 32; y += 8)
    for (int x = 8; x < 24; x += 8) regions.push_back({x, y, 8, 8});  // (the fog's columns)
  for (Integrator integrator : {Integrator::Path, Integrator::Bdpt}) {
    RenderOptions plain_options = guided_options(false), guided = guided_options(true);
    plain_options.integrator = guided.integrator = integrator;
    const RegionStats plain = stats_of(render_runs(*scene, plain_options, 6, 100), regions);
    const RegionStats with_guide = stats_of(render_runs(*scene, guided, 6, 200), regions);
    max_z(plain, with_guide);
    expect_means_agree(plain, with_guide, 0.0, integrator == Integrator::Bdpt ? "guided bdpt, fog" : "guided path, fog");
    guided.collect_stats = true;
    EXPECT_GE(render(*scene, guided).stats.guiding_medium_leaves, 1u) << "the fog's leaves learnt";
  }
}

TEST(Guiding, SameImageOnOneAndTwoThreadsAndReportsItsField) {
  const auto scene = guided_room();
  RenderOptions o = guided_options(true);
  o.spp = 16;
  expect_thread_invariant(*scene, o, {"path", "bdpt", "vcm"});
  o.collect_stats = true;
  const RenderResult r = render(*scene, o);
  // Ended after passes 1, 3 and 7; the next, to 15, would be sampled by one
  // pass only.
  EXPECT_EQ(r.stats.guiding_iterations, 3u);
  EXPECT_GE(r.stats.guiding_leaves, 1u);
  EXPECT_GT(r.stats.guiding_bytes, 0u);
}

TEST(Guiding, RefusesWhatItCannotDo) {
  const auto scene = guided_room();
  RenderOptions o = guided_options(true);
  for (Integrator other : {Integrator::Lt, Integrator::Bpm, Integrator::Ppm, Integrator::Mlt}) {
    o.integrator = other;
    EXPECT_THROW(render(*scene, o), std::invalid_argument);
  }
  o = guided_options(true);
  o.share_count = 2;
  o.film_path = "/tmp/never-written.film";
  EXPECT_THROW(render(*scene, o), std::invalid_argument);
  // MPI's ranks take units by tickets: they must share what they learn
  // (tests/mpi_test.cmake renders with them).
  RenderHooks tickets;
  tickets.next_ticket = [] { return UINT64_MAX; };
  EXPECT_THROW(render(*scene, guided_options(true), tickets), std::invalid_argument);
}
