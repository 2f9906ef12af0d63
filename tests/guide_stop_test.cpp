// Guiding stops where it does not pay (guiding/sd_tree.h, SDTree::judge;
// docs/guiding-stop.md): a field whose records' (beta L)^2 as drawn is
// more than 0.9 of what the BSDF's directions alone would have left in the
// third learning iteration, or more than 0.7 from the fourth on, stops
// guiding for the rest of the render.
#include <gtest/gtest.h>

#include <cstring>
#include <limits>
#include <string>
#include <vector>

#include "guided_rooms.h"
#include "guiding/sd_tree.h"
#include "integrator/guiding_field.h"
#include "lantern/render.h"
#include "lantern/scene.h"
#include "math/state_io.h"
#include "sanitizer.h"
#include "stop_and_resume.h"

using namespace lantern;
using namespace lantern::guiding_test;

namespace {

// n guided records in leaf 0, bin 0, each bringing the image (beta L)^2 = 1
// along a direction drawn with density `drawn` where the BSDF's is 1: the
// BSDF alone would have left `drawn` times their sum.
void feed_guided_records(SDTree& tree, float drawn, uint32_t n) {
  const uint32_t cell = tree.leaf(0).learning[0].cell_of(Vec3(0.f, 0.f, 1.f));
  for (uint32_t i = 0; i < n; ++i) tree.add({0, cell, 1.f, 1.f, 1.f, drawn, 0, 0.f, 1.f, drawn});
}

std::shared_ptr<Scene> shipped_scene(const char* name) {
  return load_scene(std::string(LANTERN_SOURCE_DIR) + "/scenes/" + name);
}

RenderOptions judged_options(Integrator integrator, int width, int height, uint32_t spp) {
  RenderOptions o = guided_options(true);
  o.integrator = integrator;
  o.guide_stop = true;
  o.collect_stats = true;
  o.width = width, o.height = height;
  o.spp = spp;
  o.seed = 1;
  return o;
}

}  // namespace

TEST(GuideStop, StopsWhereTheGuideLeavesMostOfTheBsdfsMoment) {
  GuidingSettings never;
  never.stop_where_unpaid = false;
  const Vec3 lo(0.f), hi(1.f);
  SDTree paying(lo, hi), unpaid(lo, hi), clearly(lo, hi), kept(lo, hi, never), few(lo, hi);
  for (uint32_t k = 0; k < 6; ++k) {
    feed_guided_records(paying, 10.f, 2000);    // leaves a tenth
    feed_guided_records(unpaid, 1.2f, 2000);    // leaves five sixths
    feed_guided_records(clearly, 1.05f, 2000);  // leaves 0.95
    feed_guided_records(kept, 1.2f, 2000);
    feed_guided_records(few, 1.2f, uint32_t(SDTree::kJudgeMinRecords) - 1);
    for (SDTree* t : {&paying, &unpaid, &clearly, &kept, &few}) t->update(k);
    EXPECT_EQ(unpaid.stopped(), k >= SDTree::kJudgedFully) << "after iteration " << k;
    EXPECT_EQ(clearly.stopped(), k >= SDTree::kFirstJudged) << "after iteration " << k;
  }
  EXPECT_FALSE(paying.stopped());
  EXPECT_NEAR(paying.image_share(), 0.1, 1e-6);
  EXPECT_EQ(unpaid.stopped_after(), SDTree::kJudgedFully);
  EXPECT_EQ(clearly.stopped_after(), SDTree::kFirstJudged);
  EXPECT_NEAR(clearly.image_share(), 1.0 / 1.05, 1e-6);
  EXPECT_NEAR(unpaid.image_share(), 1.0 / 1.2, 1e-6);
  EXPECT_FALSE(kept.stopped()) << "--guide-stop never";
  EXPECT_NEAR(kept.image_share(), 1.0 / 1.2, 1e-6);
  EXPECT_FALSE(few.stopped()) << "too few guided records for a verdict";
  EXPECT_EQ(few.image_share(), -1.0);
  // A guided direction the BSDF cannot draw has no weight to the BSDF's
  // density, nor does a square a float cannot hold: both are left out
  // (counted, the first would have made the BSDF's sum the largest term
  // and the guide look as if it paid).
  SDTree odd(lo, hi);
  for (uint32_t k = 0; k <= SDTree::kJudgedFully; ++k) {
    feed_guided_records(odd, 1.2f, 2000);
    odd.add({0, 0, 1.f, 1.f, 0.f, 5.f, 0, 0.f, 1.f, 5.f});
    odd.add({0, 0, 1.f, 1.f, 1.f, 5.f, 0, 0.f, std::numeric_limits<float>::infinity(), 5.f});
    odd.update(k);
  }
  EXPECT_TRUE(odd.stopped());
  EXPECT_NEAR(odd.image_share(), 1.0 / 1.2, 1e-6);
  // A stopped tree offers no leaf its guide, though it learnt one.
  EXPECT_GE(paying.guide_share(0, 0), 0.f);
  EXPECT_TRUE(unpaid.trained());
  EXPECT_LT(unpaid.guide_share(0, 0), 0.f);
  // Records drawn without a guide count alike in both sums: they water a
  // guide's gain down to what it is over all of the image's vertices.
  SDTree diluted(lo, hi);
  feed_guided_records(diluted, 10.f, 2000);
  for (int i = 0; i < 6000; ++i) diluted.add({0, 0, 1.f, 1.f, 1.f, -1.f, 1, 0.f, 1.f, 1.f});
  diluted.update(SDTree::kFirstJudged);
  EXPECT_NEAR(diluted.image_share(), 8000.0 / 26000.0, 1e-6);
}

// A field's bytes carry the verdict: a field that stopped comes back
// stopped, with nothing left to learn; bytes whose verdict cannot be (a
// stop before the third iteration, a share that is not a number) are
// refused.
TEST(GuideStop, TheVerdictComesBackFromTheFieldsBytes) {
  const Vec3 lo(0.f), hi(1.f);
  GuidingField field(lo, hi, 64);
  for (uint32_t k = 0; k <= SDTree::kJudgedFully; ++k) {
    const uint32_t cell = field.tree().leaf(0).learning[0].cell_of(Vec3(0.f, 0.f, 1.f));
    field.deposit(std::vector<GuideRecord>(2000, GuideRecord{0, cell, 1.f, 1.f, 1.f, 1.2f, 0, 0.f, 1.f, 1.2f}));
    field.end_iteration();
  }
  ASSERT_TRUE(field.tree().stopped());
  EXPECT_FALSE(field.learning()) << "nothing left to learn";
  const std::string bytes = field.save();
  GuidingField restored(lo, hi, 64);
  restored.restore(bytes);
  EXPECT_EQ(restored.save(), bytes);
  EXPECT_TRUE(restored.tree().stopped());
  EXPECT_EQ(restored.tree().stopped_after(), SDTree::kJudgedFully);
  EXPECT_FALSE(restored.learning());
  // The verdict's bytes end the tree's: u8 stopped, u32 the iteration
  // after which, f64 the share; then u8 and u8 for the subpaths guided
  // and the scattered field's bytes.
  StringWriter scattered;
  field.scatter_field().write_state(scattered);
  const size_t share_at = bytes.size() - scattered.bytes.size() - 2 - 8, after_at = share_at - 4;
  auto refused = [&](size_t at, const void* value, size_t n) {
    std::string b = bytes;
    std::memcpy(b.data() + at, value, n);
    GuidingField f(lo, hi, 64);
    EXPECT_THROW(f.restore(b), std::runtime_error);
  };
  const uint32_t early = SDTree::kFirstJudged - 1;
  refused(after_at, &early, sizeof early);
  {  // (a stop after the first iteration judged is one that can be)
    std::string b = bytes;
    const uint32_t first = SDTree::kFirstJudged;
    std::memcpy(b.data() + after_at, &first, sizeof first);
    GuidingField f(lo, hi, 64);
    EXPECT_NO_THROW(f.restore(b));
    EXPECT_EQ(f.tree().stopped_after(), SDTree::kFirstJudged);
  }
  const double nan = std::numeric_limits<double>::quiet_NaN();
  refused(share_at, &nan, sizeof nan);
  double share = 0.;
  std::memcpy(&share, bytes.data() + share_at, sizeof share);
  EXPECT_NEAR(share, restored.tree().image_share(), 0.0) << "(the offsets above)";
}

// In renders: on the tiny-light box, lobes guide the path tracer to the
// light through its reflections, pay, and go on to the end (their records
// leave 0.14 of the BSDF's sum here); on the Cornell box, lit by
// next-event estimation, the quadtree's guide does not pay (1.00 at this
// size), nor do bdpt's guided light subpaths (0.98), and both stop after
// the third iteration, recording no more. (Fixed seeds: the verdicts are
// deterministic.)
TEST(GuideStop, TheGuideGoesOnWhereItPaysAndStopsWhereItDoesNot) {
  if (LANTERN_ASAN) GTEST_SKIP() << "the verdicts of whole renders: the Release suite runs it";
  RenderOptions lobes = judged_options(Integrator::Path, 64, 64, 32);
  lobes.guide_distribution = GuideModel::Vmm;
  const RenderStats paid = render(*shipped_scene("cornell-box-tiny-light.pbrt"), lobes).stats;
  EXPECT_EQ(paid.guiding_stopped_after, -1) << "share " << paid.guiding_share;
  EXPECT_GE(paid.guiding_share, 0.0);
  EXPECT_LT(paid.guiding_share, SDTree::kPaysBelow);

  const auto box = shipped_scene("cornell-box.pbrt");
  const RenderOptions o = judged_options(Integrator::Path, 64, 48, 64);
  const RenderResult stopped = render(*box, o);
  EXPECT_EQ(stopped.stats.guiding_stopped_after, int32_t(SDTree::kFirstJudged))
      << "share " << stopped.stats.guiding_share;
  EXPECT_GT(stopped.stats.guiding_share, SDTree::kPaysBelowFirst);
  RenderOptions never = o;
  never.guide_stop = false;
  const RenderResult kept = render(*box, never);
  EXPECT_EQ(kept.stats.guiding_stopped_after, -1);
  // 64 spp learn in passes 0 to 30; stopped after pass 6, about a fifth.
  EXPECT_LT(double(stopped.stats.guiding_records), 0.3 * double(kept.stats.guiding_records));
  EXPECT_NE(stopped.image.rgb, kept.image.rgb);

  RenderOptions light = judged_options(Integrator::Bdpt, 64, 48, 32);
  light.guiding = false, light.guide_light_subpaths = true;
  const RenderStats light_stopped = render(*box, light).stats;
  EXPECT_EQ(light_stopped.guiding_light_stopped_after, int32_t(SDTree::kFirstJudged))
      << "share " << light_stopped.guiding_light_share;
  EXPECT_EQ(light_stopped.guiding_stopped_after, -1) << "(no radiance field)";
}

// A checkpoint carries the verdict: bdpt's guide in the guided room stops
// after pass 6 of 32, and a render stopped before and after that, on one
// and two threads in turn, resumes to the straight render's image bit for
// bit. (With the verdict left out of the field's bytes, the resumed runs
// guided again and the images differed: checked.)
TEST(GuideStop, ResumesAcrossTheStopToTheStraightImage) {
  const auto scene = guided_room();
  RenderOptions o = judged_options(Integrator::Bdpt, 32, 32, 32);
  o.maxdepth = 5;
  o.wave_size = 128;  // 8 waves a pass: the runs stop after passes 4 and 15
  EXPECT_EQ(render(*scene, o).stats.guiding_stopped_after, int32_t(SDTree::kFirstJudged));
  o.collect_stats = false;
  expect_resumes_to_the_straight_image(*scene, o, "lantern_guide_stop_resume.ckpt", 40, 45, 3, "bdpt");
}
