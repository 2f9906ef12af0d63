// Guided distances in media: the scattered radiance field's walk along a
// segment and what it learns, the guided distance density against its
// samples (chi-square) and its integral, and the guided path tracer in fog
// against the unguided one (region means over seeds) and across a resume.
#include "integrator/guided_distance.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <cstring>
#include <random>

#include "bsdf_checks.h"
#include "guided_rooms.h"
#include "guiding/scatter_field.h"
#include "lantern/render.h"
#include "lantern/scene.h"
#include "math/state_io.h"
#include "sanitizer.h"
#include "stat_compare.h"
#include "stop_and_resume.h"

using namespace lantern;

namespace {

// A field over a 4 x 3 x 8 room whose records came mostly from a slab
// (x < 1, a beam's worth of fog) and were brighter there: split, then
// taught each leaf's mean.
ScatterField slab_field() {
  ScatterField f(Vec3(0.f), Vec3(4.f, 3.f, 8.f));
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> u(0.f, 1.f);
  for (uint32_t iteration = 0; iteration < 2; ++iteration) {
    for (int i = 0; i < 200000; ++i) {
      const bool slab = i % 4 != 0;
      const Vec3 p(slab ? u(rng) : 4.f * u(rng), 3.f * u(rng), 8.f * u(rng));
      f.add(f.leaf_of(p), p.x < 1.f ? 10.f * (1.f + p.z) : 0.2f);
    }
    f.update(iteration);
  }
  return f;
}

}  // namespace

// The leaves a segment crosses are the leaves of its points, in order,
// end to end, from where it enters the field's cube to where it leaves.
TEST(ScatterField, LeavesAlongASegmentAreItsPointsLeavesInOrder) {
  const ScatterField f = slab_field();
  ASSERT_GT(f.leaf_count(), 50u);
  std::mt19937 rng(9);
  std::uniform_real_distribution<float> u(-1.f, 1.f);
  int crossings = 0;
  for (int i = 0; i < 2000; ++i) {
    const Vec3 o(2.f + 3.f * u(rng), 1.5f + 2.f * u(rng), 4.f + 5.f * u(rng));
    const Vec3 d = glm::normalize(Vec3(u(rng), u(rng), u(rng)));
    const float len = i % 3 == 0 ? kInfinity : 6.f * (1.f + u(rng));
    float end = -1.f;
    f.leaves_along(o, d, 0.f, len, [&](float ta, float tb, uint32_t leaf) {
      ASSERT_LT(ta, tb);
      if (end >= 0.f) EXPECT_EQ(ta, end) << "end to end";
      EXPECT_GE(ta, 0.f);
      EXPECT_LE(tb, len);
      end = tb;
      EXPECT_EQ(f.leaf_of(o + d * (0.5f * (ta + tb))), leaf) << "segment " << i;
      ++crossings;
    });
    // Just past the last stretch the segment is over or outside the cube
    // (8.08 m wide, around the room's centre).
    if (end >= 0.f && end < len) {
      const Vec3 q = glm::abs(o + d * (end + 1e-3f) - Vec3(2.f, 1.5f, 4.f));
      EXPECT_GT(max_component(q), 4.03f) << "segment " << i << " ends inside at " << end;
    }
  }
  EXPECT_GT(crossings, 5000);
}

// A leaf's level is its records' mean; a leaf no record reached keeps what
// it knew; the state comes back bit for bit and damaged bytes are refused.
TEST(ScatterField, LearnsMeansAndRoundTrips) {
  ScatterField f(Vec3(0.f), Vec3(1.f));
  EXPECT_FALSE(f.trained());
  f.add(0, 1.f), f.add(0, 3.f);
  f.update(0);
  EXPECT_TRUE(f.trained());
  EXPECT_EQ(f.level(0), 2.f);
  f.update(1);
  EXPECT_EQ(f.level(0), 2.f) << "no records: kept";
  const ScatterField g = slab_field();
  StringWriter out;
  g.write_state(out);
  ScatterField back(Vec3(0.f), Vec3(4.f, 3.f, 8.f));
  StringReader in(out.bytes);
  back.read_state(in);
  StringWriter again;
  back.write_state(again);
  EXPECT_EQ(again.bytes, out.bytes);
  ScatterField elsewhere(Vec3(1.f), Vec3(4.f, 3.f, 8.f));
  StringReader in2(out.bytes);
  EXPECT_THROW(elsewhere.read_state(in2), std::runtime_error);
  std::string cut = out.bytes.substr(0, out.bytes.size() / 2);
  StringReader in3(cut);
  ScatterField short_of(Vec3(0.f), Vec3(4.f, 3.f, 8.f));
  EXPECT_THROW(short_of.read_state(in3), std::runtime_error);
  std::string loop = out.bytes;
  const uint32_t none = 0;  // the root without its first child, with its second
  std::memcpy(loop.data() + 12 + 4 + 1 + 8, &none, 4);
  StringReader in4(loop);
  EXPECT_THROW(short_of.read_state(in4), std::runtime_error);
}

// Along a segment through the slab and out of it, the guide's density
// integrates to one and its samples follow it (chi-square over 100 bins),
// with and without extinction.
TEST(DistanceGuide, DensityIntegratesToOneAndMatchesItsSamples) {
  const ScatterField f = slab_field();
  const Vec3 o(0.3f, 1.2f, 0.5f), d = glm::normalize(Vec3(1.f, 0.2f, 0.6f));
  for (float sigma : {0.f, 0.4f, 3.f}) {
    DistanceGuide g;
    const float len = 5.f;
    ASSERT_TRUE(g.build(f, o, d, len, sigma));
    constexpr int kBins = 100, kSteps = 200;
    std::vector<double> expected(kBins, 0.0), observed(kBins, 0.0);
    double integral = 0.0;
    for (int b = 0; b < kBins; ++b)
      for (int s = 0; s < kSteps; ++s) {
        const float t = len * (float(b) + (float(s) + 0.5f) / kSteps) / kBins;
        const double mass = g.pdf(t) * double(len) / (kBins * kSteps);
        expected[size_t(b)] += mass;
        integral += mass;
      }
    EXPECT_NEAR(integral, 1.0, 2e-3) << "sigma " << sigma;
    std::mt19937 rng(17);
    std::uniform_real_distribution<float> u(0.f, 1.f);
    const int n = 200000;
    for (int i = 0; i < n; ++i) {
      const float t = g.sample(u(rng));
      ASSERT_TRUE(t >= 0.f && t < len);
      ASSERT_GT(g.pdf(t), 0.f) << "a sample where the density is zero";
      observed[std::min(size_t(kBins - 1), size_t(t / len * kBins))] += 1.0;
    }
    double chi2 = 0.0;
    int dof = 0;
    for (int b = 0; b < kBins; ++b) {
      const double e = expected[size_t(b)] * n;
      if (e < 5.0) continue;
      chi2 += (observed[size_t(b)] - e) * (observed[size_t(b)] - e) / e;
      ++dof;
    }
    EXPECT_LT(chi2, bsdf_checks::chi2_critical(dof - 1)) << "sigma " << sigma;
    // The bright slab (x < 1, the first metre or so) holds most of it.
    EXPECT_GT(expected[0] + expected[10], 5.0 * (expected[60] + expected[70])) << "sigma " << sigma;
  }
  DistanceGuide none;
  EXPECT_FALSE(none.build(ScatterField(Vec3(0.f), Vec3(1.f)), o, d, 5.f, 0.4f)) << "nothing learnt";
}

namespace {

// A room of coloured fog, crossed by a spot light's beam: free flight
// seldom scatters inside the beam, which next-event estimation reaches
// from there alone. The room is open towards the camera, which stands
// outside it in the same fog, so the camera rays that miss the room go on
// for ever; in the beam hangs a ball of denser, glowing fog, which rays
// cross into and out of (stretches that start deep in the ray's optical
// depth, and emission found where a guided point lies). The spot sits in a ball without fog: a point light
// in fog gives next-event estimates as large as 1 / r^2 near it, whose
// variance is infinite, and the test's standard errors would say nothing.
std::shared_ptr<Scene> beam_room() {
  return load_scene_from_string(R"(
MakeNamedMedium "fog" "string type" [ "homogeneous" ]
  "rgb sigma_a" [ 0.05 0.1 0.02 ] "rgb sigma_s" [ 0.3 0.2 0.4 ] "float g" [ 0.3 ]
MediumInterface "" "fog"
LookAt 0 1.2 -5.5  0 1 0  0 1 0
Camera "perspective" "float fov" [ 70 ]
Film "rgb" "integer xresolution" [ 48 ] "integer yresolution" [ 48 ]
WorldBegin
LightSource "spot" "point3 from" [ -1.8 1.9 0 ] "point3 to" [ 1 0 1 ] "float coneangle" [ 8 ] "float conedeltaangle" [ 2 ]
  "rgb I" [ 60 60 60 ]
AttributeBegin
  MediumInterface "" "fog"
  Material "interface"
  Translate -1.8 1.9 0
  Shape "sphere" "float radius" [ 0.3 ]
AttributeEnd
Material "diffuse" "rgb reflectance" [ 0.6 0.5 0.4 ]
Shape "trianglemesh" "point3 P" [ -2 0 -3  2 0 -3  2 0 2  -2 0 2 ] "integer indices" [ 0 1 2 0 2 3 ]
Shape "trianglemesh" "point3 P" [ -2 2 -3  -2 2 2  2 2 2  2 2 -3 ] "integer indices" [ 0 1 2 0 2 3 ]
Shape "trianglemesh" "point3 P" [ -2 0 2  2 0 2  2 2 2  -2 2 2 ] "integer indices" [ 0 1 2 0 2 3 ]
Shape "trianglemesh" "point3 P" [ -2 0 -3  -2 0 2  -2 2 2  -2 2 -3 ] "integer indices" [ 0 1 2 0 2 3 ]
Shape "trianglemesh" "point3 P" [ 2 0 -3  2 2 -3  2 2 2  2 0 2 ] "integer indices" [ 0 1 2 0 2 3 ]
MakeNamedMedium "glow" "string type" [ "homogeneous" ]
  "rgb sigma_a" [ 0.4 0.2 0.3 ] "rgb sigma_s" [ 1.0 1.4 0.8 ] "float g" [ -0.2 ] "rgb Le" [ 0.2 0.1 0.05 ]
AttributeBegin
  MediumInterface "glow" "fog"
  Material "interface"
  Translate -0.2 1.0 0.6
  Shape "sphere" "float radius" [ 0.35 ]
AttributeEnd
)",
                                "beam-room.pbrt");
}

// The guiding tests' options (path, 64 spp), four bounces.
RenderOptions beam_options(bool guiding) {
  RenderOptions o = guiding_test::guided_options(guiding);
  o.maxdepth = 4;
  return o;
}

}  // namespace

// The guided path tracer, whose points in the fog are drawn from the
// guided mixture, converges to the unguided image (16 renders a side, 3 x 3
// regions: within 2.1 standard errors as built). Checked: with the weight
// divided by free flight's density alone (not the mixture's the point was
// drawn with), the means lie 20 standard errors off; with the stretch's
// scattering probability P missing the transmittance before it, 5.9. (A
// wrong P for rays that escape is not seen: little light scatters along
// them inside the field's cube.)
TEST(Guiding, GuidedDistancesConvergeToTheUnguidedImage) {
  if (LANTERN_ASAN) GTEST_SKIP() << "statistics only: the Release suite runs it";
  const auto scene = beam_room();
  std::vector<Region> regions;
  for (int y = 0; y < 48; y += 16)
    for (int x = 0; x < 48; x += 16) regions.push_back({x, y, 16, 16});
  RenderOptions plain_options = beam_options(false), guided_options = beam_options(true);
  plain_options.spp = guided_options.spp = 64;
  const RegionStats plain = stats_of(render_runs(*scene, plain_options, 16, 100), regions);
  const RegionStats guided = stats_of(render_runs(*scene, guided_options, 16, 200), regions);
  max_z(plain, guided);
  expect_means_agree(plain, guided, 0.0, "guided distances");
  RenderOptions o = beam_options(true);
  o.collect_stats = true;
  const RenderResult r = render(*scene, o);
  EXPECT_GE(r.stats.guiding_distance_lit_leaves, 2u) << "the fog's leaves learnt";
  EXPECT_GE(r.stats.guiding_distance_leaves, r.stats.guiding_distance_lit_leaves);
}

// A checkpoint carries the scattered radiance field: a guided render in
// fog stopped inside its iterations and resumed makes the straight
// render's image bit for bit (resumed without the field, it did not:
// checked).
TEST(Guiding, ResumesWithTheDistancesItLearnt) {
  const auto scene = beam_room();
  RenderOptions o = beam_options(true);
  o.spp = 16;        // iterations end after passes 1, 3 and 7
  o.wave_size = 96;  // 6 waves a pass: stops fall inside passes
  expect_resumes_to_the_straight_image(*scene, o, "lantern_guided_distances.ckpt", 7, 11, 4, "path in fog");
}

// The scattered radiance field's records are added in wave order: the
// guided image in fog depends on the seed, not on the threads.
TEST(Guiding, GuidedDistancesAreTheSameOnOneAndTwoThreads) {
  RenderOptions o = beam_options(true);
  o.spp = 16;
  expect_thread_invariant(*beam_room(), o, {"path"});
}
