// Guiding with a mixture of von Mises-Fisher lobes (guiding/vmf_mixture.h,
// `--guide-distribution vmm`): the packed directions, the fitted density's
// integral and its samples (chi-square), the fit against a lobe of known
// mean and concentration, sums that do not depend on the records' order,
// the state, and guided renders against unguided ones (region means over
// seeds) and across thread counts (bit for bit).
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <random>

#include "bsdf_checks.h"
#include "guided_rooms.h"
#include "guiding/sd_tree.h"
#include "guiding/vmf_mixture.h"
#include "integrator/guide_vertices.h"
#include "lantern/render.h"
#include "lantern/scene.h"
#include "math/equal_area.h"
#include "math/state_io.h"
#include "sanitizer.h"
#include "stat_compare.h"

using namespace lantern;
using namespace lantern::guiding_test;

namespace {

constexpr int kSquareGrid = 64;

// A lobe's density, written out here (Fisher 1953) rather than taken from
// the class.
double vmf_density(const Vec3& mean, double kappa, const Vec3& w) {
  return kappa / (2.0 * M_PI * (1.0 - std::exp(-2.0 * kappa))) * std::exp(kappa * (double(glm::dot(mean, w)) - 1.0));
}

// Fits a mixture to records of directions drawn uniformly over the sphere
// with energy target(w) / (1 / 4π): `rounds` iterations of learning.
template <class Target>
VmfMixture fitted(Target target, int rounds, int records) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> u(0.f, 1.f);
  VmfMixture m;
  for (int round = 0; round < rounds; ++round) {
    VmfMixture learning = m.refined();
    for (int i = 0; i < records; ++i) {
      const Vec3 w = glm::normalize(equal_area_square_to_sphere(Vec2(u(rng), u(rng))));
      learning.add(VmfMixture::cell_of(w), float(target(w) * 4.0 * M_PI), 0.f);
    }
    learning.sum_up();
    m = learning;
  }
  return m;
}

const Vec3 kMeanA = glm::normalize(Vec3(0.3f, -0.5f, 0.8f)), kMeanB = glm::normalize(Vec3(-0.7f, 0.6f, -0.2f));
double two_lobes(const Vec3& w) { return 0.6 * vmf_density(kMeanA, 60.0, w) + 0.4 * vmf_density(kMeanB, 8.0, w); }

}  // namespace

TEST(VmfMixture, PackedDirectionsComeBackWithinATenThousandthOfARadian) {
  std::mt19937 rng(2);
  std::uniform_real_distribution<float> u(0.f, 1.f);
  std::vector<Vec3> dirs = {Vec3(1, 0, 0),
                            Vec3(-1, 0, 0),
                            Vec3(0, 1, 0),
                            Vec3(0, -1, 0),
                            Vec3(0, 0, 1),
                            Vec3(0, 0, -1),
                            glm::normalize(Vec3(1, 1, 0)),
                            glm::normalize(Vec3(-1, 1, -1e-6f)),
                            glm::normalize(Vec3(1e-7f, -1, -1))};
  for (int i = 0; i < 200000; ++i) dirs.push_back(glm::normalize(equal_area_square_to_sphere(Vec2(u(rng), u(rng)))));
  double worst = 0.0;
  for (const Vec3& w : dirs) {
    const Vec3 back = VmfMixture::cell_direction(VmfMixture::cell_of(w));
    // (the chord, in double: acos of a float near 1 has steps of 3e-4)
    const double e = std::sqrt(sqr(double(w.x) - back.x) + sqr(double(w.y) - back.y) + sqr(double(w.z) - back.z));
    worst = std::max(worst, e);
  }
  EXPECT_LT(worst, 1e-4);
}

// The fitted mixture's density integrates to one over the sphere, and its
// samples follow it (chi-square over the 64 x 64 grid of the equal-area
// square, whose cells are equal in solid angle, each cell's probability
// from 8 x 8 points of it); each sample's density is the density at its
// direction.
TEST(VmfMixture, DensityIntegratesToOneAndMatchesItsSamples) {
  const VmfMixture m = fitted(two_lobes, 4, 40000);
  std::vector<double> expected(kSquareGrid * kSquareGrid, 0.0);
  double integral = 0.0;
  constexpr int kSub = 8;
  for (int y = 0; y < kSquareGrid; ++y)
    for (int x = 0; x < kSquareGrid; ++x) {
      double p = 0.0;
      for (int sy = 0; sy < kSub; ++sy)
        for (int sx = 0; sx < kSub; ++sx) {
          const Vec2 q((x + (sx + 0.5f) / kSub) / kSquareGrid, (y + (sy + 0.5f) / kSub) / kSquareGrid);
          p += m.sphere_pdf(glm::normalize(equal_area_square_to_sphere(q)), m.pivot());
        }
      p *= 4.0 * M_PI / double(kSquareGrid * kSquareGrid * kSub * kSub);
      expected[size_t(y * kSquareGrid + x)] = p;
      integral += p;
    }
  EXPECT_NEAR(integral, 1.0, 2e-3);

  const int n = 400000;
  std::vector<double> observed(kSquareGrid * kSquareGrid, 0.0);
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> u(0.f, 1.f);
  int differing = 0;
  for (int i = 0; i < n; ++i) {
    float pdf = 0.f;
    const Vec3 w = m.sample(Vec2(u(rng), u(rng)), m.pivot(), &pdf);
    ASSERT_NEAR(glm::length(w), 1.f, 1e-5f);
    if (std::fabs(pdf - m.sphere_pdf(w, m.pivot())) > 1e-5f * pdf) ++differing;
    const Vec2 p = equal_area_sphere_to_square(w);
    const int bx = std::min(kSquareGrid - 1, int(p.x * kSquareGrid)),
              by = std::min(kSquareGrid - 1, int(p.y * kSquareGrid));
    observed[size_t(by * kSquareGrid + bx)] += 1.0;
  }
  EXPECT_EQ(differing, 0);
  for (double& e : expected) e *= n;
  bsdf_checks::expect_counts_fit(observed, expected, "lobes' draws");
}

// Records of one lobe (mean kMeanA, κ = 300), drawn from it by inversion:
// after three iterations the mixture's density near the mean is the
// lobe's, within 15% at the mean and 25% at 0.05 and 0.1 radians off it.
TEST(VmfMixture, FitFindsALobesMeanAndConcentration) {
  const double kappa = 300.0;
  std::mt19937 rng(9);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const Vec3 t1 = glm::normalize(glm::cross(kMeanA, Vec3(0, 0, 1))), t2 = glm::cross(kMeanA, t1);
  VmfMixture m;
  for (int round = 0; round < 3; ++round) {
    VmfMixture learning = m.refined();
    for (int i = 0; i < 20000; ++i) {
      const double c = 1.0 + std::log(1.0 - u(rng)) / kappa;  // (e^{-2κ} is 0 in double here)
      const double s = std::sqrt(std::max(0.0, 1.0 - c * c)), phi = 2.0 * M_PI * u(rng);
      const Vec3 w = glm::normalize(float(c) * kMeanA + float(s * std::cos(phi)) * t1 + float(s * std::sin(phi)) * t2);
      learning.add(VmfMixture::cell_of(w), 1.f, 0.f);
    }
    learning.sum_up();
    m = learning;
  }
  for (double angle : {0.0, 0.05, 0.1}) {
    const Vec3 w = glm::normalize(float(std::cos(angle)) * kMeanA + float(std::sin(angle)) * t1);
    const double want = vmf_density(kMeanA, kappa, w);
    EXPECT_NEAR(m.sphere_pdf(w, m.pivot()) / want, 1.0, angle == 0.0 ? 0.15 : 0.25) << angle << " radians off the mean";
  }
}

// Parallax: records of a patch 3 m above the pivot (directions and
// inverse distances from the pivot, as GuideVertices::make_records makes
// them), and a vertex 1 m to the side of the pivot. The lobe is re-aimed
// at the patch from there: its density towards the patch is far above
// its density along the pivot's direction, and its samples' mean
// direction points at the patch.
TEST(VmfMixture, LobesAreReAimedAtWhatTheyPointAtFromEachVertex) {
  std::mt19937 rng(6);
  std::uniform_real_distribution<float> u(-1.f, 1.f);
  const Vec3 patch(0.f, 0.f, 3.f), vertex(1.f, 0.f, 0.f);
  VmfMixture m;
  ASSERT_EQ(m.pivot(), Vec3(0.f));
  for (int round = 0; round < 3; ++round) {
    VmfMixture learning = m.refined();
    for (int i = 0; i < 20000; ++i) {
      const Vec3 t = patch + 0.05f * Vec3(u(rng), u(rng), 0.f);
      learning.add(VmfMixture::cell_of(glm::normalize(t)), 1.f, 1.f / glm::length(t));
    }
    learning.sum_up();
    m = learning;
  }
  const Vec3 towards = glm::normalize(patch - vertex);
  EXPECT_GT(m.sphere_pdf(towards, vertex), 20.f * m.sphere_pdf(Vec3(0.f, 0.f, 1.f), vertex));
  Vec3 sum(0.f);
  std::uniform_real_distribution<float> v(0.f, 1.f);
  for (int i = 0; i < 20000; ++i) {
    float pdf = 0.f;
    sum += m.sample(Vec2(v(rng), v(rng)), vertex, &pdf);
  }
  EXPECT_LT(std::acos(std::min(1.f, glm::dot(glm::normalize(sum), towards))), 0.03f);
}

// A record's direction and distance for a mixture: from the leaf's pivot
// to the point its path's ray reached (reached(), also where the path
// ended there), else to its next vertex, else none (inverse distance 0,
// its own direction).
TEST(VmfMixture, RecordsAimFromThePivotAtWhereTheirPathWentOn) {
  GuidingSettings settings;
  settings.distribution = GuideDistributionKind::kMixture;
  const SDTree tree(Vec3(0.f), Vec3(4.f), settings);
  const Vec3 pivot = tree.leaf(0).learning[0].pivot();
  ASSERT_LT(glm::length(pivot - Vec3(2.f)), 1e-5f);
  GuideVertices g;
  const Vec3 up(0.f, 0.f, 1.f);
  for (uint32_t slot : {3u, 5u, 7u}) g.push(slot, 0, Vec3(1.f), 0, up, 1.f, 1.f, 1.f, -1.f, Spectrum(1.f));
  std::vector<Spectrum> path_L(8, Spectrum(0.f));
  g.end_bounce(path_L);
  const Vec3 hit(1.f, 1.f, 3.5f), next(3.f, 3.f, 3.f);
  g.reached(3, hit);                                              // a ray that reached a light
  g.push(5, 0, next, 0, up, 1.f, 1.f, 1.f, -1.f, Spectrum(1.f));  // a vertex made there
  g.end_bounce(path_L);
  for (Spectrum& l : path_L) l = Spectrum(2.f);
  std::vector<GuideRecord> out;
  g.make_records(path_L, tree, 1, out);
  ASSERT_EQ(out.size(), 4u);
  const auto expect_aimed = [&](const GuideRecord& r, const Vec3& at) {
    EXPECT_NEAR(r.inv_distance, 1.f / glm::length(at - pivot), 1e-6f);
    EXPECT_GT(glm::dot(VmfMixture::cell_direction(r.cell), glm::normalize(at - pivot)), 0.99999f);
  };
  expect_aimed(out[0], hit);
  expect_aimed(out[1], next);
  EXPECT_EQ(out[2].inv_distance, 0.f);  // its ray reached nothing known
  EXPECT_GT(glm::dot(VmfMixture::cell_direction(out[2].cell), up), 0.99999f);
}

// In a render, the eye subpaths' records learn where their rays went: in a
// closed room most of them (the rest end where no ray was traced), with
// lobes; none with the quadtree, whose records are directions. The light
// subpaths' records carry no distance (docs/guiding-lobes.md).
TEST(GuidingLobes, RecordsLearnWhereTheirRaysWent) {
  const auto scene = guided_room();
  RenderOptions o = bdpt_options(1.f);
  o.guiding = o.guide_light_subpaths = true;
  o.guide_distribution = GuideModel::Vmm;
  o.spp = 8;
  o.collect_stats = true;
  const RenderStats lobes = render(*scene, o).stats;
  ASSERT_GT(lobes.guiding_records, 1000u);
  EXPECT_GT(lobes.guiding_records_aimed, lobes.guiding_records / 2);
  EXPECT_GT(lobes.guiding_light_records, 1000u);
  o.guide_distribution = GuideModel::Quadtree;
  const RenderStats quadtree = render(*scene, o).stats;
  EXPECT_GT(quadtree.guiding_records, 1000u);
  EXPECT_EQ(quadtree.guiding_records_aimed, 0u);
}

// The sums do not depend on the order records arrive in (fixed-point:
// math/fixed_sum.h), so the fit does not either, bit for bit; and the
// state comes back bit for bit, and is refused where it cannot be.
TEST(VmfMixture, FitDoesNotDependOnTheRecordsOrderAndItsStateComesBack) {
  std::mt19937 rng(4);
  std::uniform_real_distribution<float> u(0.f, 1.f);
  std::vector<std::pair<uint32_t, float>> records;
  for (int i = 0; i < 5000; ++i) {
    const Vec3 w = glm::normalize(equal_area_square_to_sphere(Vec2(u(rng), u(rng))));
    records.push_back({VmfMixture::cell_of(w), float(two_lobes(w)) * (0.5f + u(rng))});
  }
  VmfMixture forward = VmfMixture().refined(), backward = forward;
  for (const auto& [cell, e] : records) forward.add(cell, e, 0.f);
  for (auto r = records.rbegin(); r != records.rend(); ++r) backward.add(r->first, r->second, 0.f);
  forward.sum_up(), backward.sum_up();
  StringWriter a, b;
  forward.write_state(a), backward.write_state(b);
  EXPECT_EQ(a.bytes, b.bytes);

  VmfMixture back;
  StringReader in(a.bytes);
  back.read_state(in);
  StringWriter again;
  back.write_state(again);
  EXPECT_EQ(again.bytes, a.bytes);
  const Vec3 w = glm::normalize(Vec3(0.2f, 0.4f, -0.3f));
  EXPECT_EQ(back.sphere_pdf(w, Vec3(0.f)), forward.sphere_pdf(w, Vec3(0.f)));

  // A lobe's weight beyond 1 (the first lobe's weight: after the pivot,
  // the lobe count, the lobe's mean and κ).
  std::string bad = a.bytes;
  const float two = 2.f;
  std::memcpy(bad.data() + sizeof(Vec3) + sizeof(uint64_t) + sizeof(Vec3) + sizeof(float), &two, sizeof two);
  VmfMixture refused;
  StringReader bad_in(bad);
  EXPECT_THROW(refused.read_state(bad_in), std::runtime_error);
}

// Paths guided by lobes converge to the unguided image: region means over
// independent runs agree within 4.5 standard errors, for the path tracer
// and for bdpt's and vcm's eye subpaths (the sky seen through a hole in
// the ceiling makes the lobes narrow).
TEST(GuidingLobes, ConvergeToTheUnguidedImages) {
  if (LANTERN_ASAN) GTEST_SKIP() << "statistics only: the Release suite runs it";
  const auto scene = skylit_room();
  std::vector<Region> regions;
  for (int y = 0; y < 32; y += 8)
    for (int x = 0; x < 32; x += 8) regions.push_back({x, y, 8, 8});
  for (Integrator integrator : {Integrator::Path, Integrator::Bdpt, Integrator::Vcm}) {
    RenderOptions plain_options = guided_options(false), guided = guided_options(true);
    plain_options.integrator = guided.integrator = integrator;
    guided.guide_distribution = GuideModel::Vmm;
    const RegionStats plain = stats_of(render_runs(*scene, plain_options, 6, 100), regions);
    const RegionStats with_guide = stats_of(render_runs(*scene, guided, 6, 200), regions);
    max_z(plain, with_guide);
    expect_means_agree(plain, with_guide, 0.0, (std::string("lobes, ") + name(integrator)).c_str());
    guided.collect_stats = true;
    const RenderResult r = render(*scene, guided);
    EXPECT_GE(r.stats.guiding_iterations, 2u);
  }
}

// The same image on one and two threads, bit for bit, and another image
// than the quadtree's (the lobes were learnt and sampled).
TEST(GuidingLobes, SameImageOnOneAndTwoThreads) {
  const auto scene = guided_room();
  RenderOptions o = guided_options(true);
  o.spp = 16;
  o.guide_distribution = GuideModel::Vmm;
  expect_thread_invariant(*scene, o, {"path", "bdpt", "vcm"});
  RenderOptions quadtree = o;
  quadtree.guide_distribution = GuideModel::Quadtree;
  EXPECT_NE(render(*scene, o).image.rgb, render(*scene, quadtree).image.rgb);
}
