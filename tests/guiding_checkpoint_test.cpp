// Guided renders' checkpoints: the field comes back with the film, bit for
// bit (stops and resumes against the straight render), checkpoints of
// earlier formats are refused by their version, and a field's
// bytes that cannot be one are refused.
#include <gtest/gtest.h>

#include <cstdio>
#include <cstring>
#include <fstream>
#include <random>

#include "film/checkpoint.h"
#include "film/film.h"
#include "guided_rooms.h"
#include "guiding/sd_tree.h"
#include "integrator/guiding_field.h"
#include "lantern/error.h"
#include "lantern/render.h"
#include "lantern/scene.h"
#include "math/equal_area.h"
#include "sanitizer.h"
#include "stop_and_resume.h"

using namespace lantern;
using namespace lantern::guiding_test;

// A checkpoint carries the field with the film: a guided render stopped
// inside its iterations of learning (and after them) and resumed, on one
// and two threads in turn, makes the straight render's image bit for bit.
// Resumed without the field (checked by leaving restore out), paths drew
// other directions and the image differed. Fields of lobes too.
TEST(Guiding, ResumesWithTheFieldItLearnt) {
  const auto scene = guided_room();
  // (Under the sanitizers the path tracer alone: the field's bytes are the
  // same code for all three.)
  const std::vector<Integrator> integrators =
      LANTERN_ASAN ? std::vector<Integrator>{Integrator::Path}
                   : std::vector<Integrator>{Integrator::Path, Integrator::Bdpt, Integrator::Vcm};
  for (Integrator integrator : integrators) {
    RenderOptions o = guided_options(true);
    o.integrator = integrator;
    o.spp = 16;          // iterations end after passes 1, 3 and 7
    o.wave_size = 128;   // 8 waves a pass: stops fall inside passes
    expect_resumes_to_the_straight_image(*scene, o, "lantern_guided_resume.ckpt", 7, 11, 4, name(integrator));
  }
  // A field of lobes (--guide-distribution vmm) as well.
  {
    RenderOptions o = guided_options(true);
    o.spp = 16, o.wave_size = 128;
    o.guide_distribution = GuideModel::Vmm;
    expect_resumes_to_the_straight_image(*scene, o, "lantern_guided_resume_lobes.ckpt", 7, 11, 4, "lobes");
  }
  // Its iterations are planned from the budget: a larger one cannot go on
  // from it.
  RenderOptions o = guided_options(true);
  o.spp = 8;
  o.checkpoint_path = ::testing::TempDir() + "/lantern_guided_extend.ckpt";
  o.keep_checkpoint = true;
  render(*scene, o);
  o.spp = 16;
  o.resume = true;
  EXPECT_THROW(render(*scene, o), InputError);
  // Guided checkpoints of formats 3 to 6 (before media had distributions,
  // before light subpaths were guided, before fixed-point sums and guided
  // distances, before the fields judged whether they pay) are refused by
  // their version, with what to do.
  o.spp = 8;
  for (const uint32_t format : {3u, 4u, 5u, 6u}) {
    {
      std::fstream f(o.checkpoint_path, std::ios::in | std::ios::out | std::ios::binary);
      f.seekp(8);
      f.write(reinterpret_cast<const char*>(&format), sizeof format);
    }
    try {
      render(*scene, o);
      ADD_FAILURE() << "a format " << format << " checkpoint was resumed";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find("earlier Lantern version"), std::string::npos) << e.what();
    }
  }
  std::remove(o.checkpoint_path.c_str());
}

// The field's bytes in a checkpoint: a learnt field comes back bit for bit,
// and bytes that cannot be a field (cut short, a count beyond them, a node
// with two parents, another scene's bounds) are refused with an
// error, never a crash or a walk without end. (A damaged file fails its
// checksum first; these are files whose checksum was made to fit.)
TEST(Guiding, FieldBytesRoundTripAndBadOnesAreRefused) {
  const Vec3 lo(-1.f), hi(2.f);
  GuidingField field(lo, hi, 64);
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> u(0.f, 1.f);
  for (int iteration = 0; iteration < 5; ++iteration) {
    std::vector<GuideRecord> records;
    for (int i = 0; i < 30000; ++i) {
      const Vec3 p = lo + (hi - lo) * Vec3(u(rng), u(rng), u(rng));
      GuideRecord r{};
      r.leaf = field.tree().leaf_of(p);
      r.bin = uint8_t(i % SDTree::kBins);
      r.cell = field.tree().leaf(r.leaf).learning[r.bin].cell_of(
          equal_area_square_to_sphere(Vec2(0.1f + 0.3f * u(rng), u(rng))));
      r.energy = 1.f + u(rng);
      r.second = r.energy, r.bsdf_pdf = 0.3f, r.guide_pdf = i % 2 ? 0.3f : -1.f;
      // (the guided half drawn with 10 times the BSDF's density: a guide
      // that pays, judged after iteration 3 and going on)
      r.image = r.energy, r.drawn_pdf = 3.f;
      records.push_back(r);
    }
    field.deposit(records);
    if (iteration < 4) field.end_iteration();  // (the fifth iteration's sums stay under way)
  }
  const std::string bytes = field.save();
  ASSERT_GT(field.tree().leaves().size(), 1u);  // (it split)
  ASSERT_FALSE(field.tree().stopped());
  ASSERT_GT(field.tree().image_share(), 0.0);
  GuidingField restored(lo, hi, 64);
  restored.restore(bytes);
  EXPECT_EQ(restored.save(), bytes);
  EXPECT_EQ(restored.iteration(), field.iteration());

  auto refused = [&](std::string b) {
    GuidingField f(lo, hi, 64);
    EXPECT_THROW(f.restore(b), std::runtime_error);
    EXPECT_EQ(f.iteration(), 0u);  // (left as it was)
  };
  refused(bytes.substr(0, bytes.size() / 2));
  refused(bytes + "x");
  // Layout: u32 iteration, u8 done, the tree: Vec3 lo, float extent, u8
  // trained, u64 node count, nodes of (u32 child[2], u32 leaf, u8 axis).
  constexpr size_t kNodeCount = 4 + 1 + 12 + 4 + 1, kFirstNode = kNodeCount + 8;
  std::string huge = bytes;
  std::memset(huge.data() + kNodeCount, 0xff, 8);
  refused(huge);
  std::string half = bytes;  // the root's children 0 and 1: neither a leaf nor an inner node
  const uint32_t children[2] = {0, 1};
  std::memcpy(half.data() + kFirstNode, children, sizeof children);
  refused(half);
  std::string shared = bytes;  // both children the same node: a node with two parents
  uint32_t root[2];
  std::memcpy(root, bytes.data() + kFirstNode, sizeof root);
  ASSERT_NE(root[0], 0u);
  root[1] = root[0];
  std::memcpy(shared.data() + kFirstNode, root, sizeof root);
  refused(shared);
  GuidingField elsewhere(lo, hi + Vec3(1.f), 64);
  EXPECT_THROW(elsewhere.restore(bytes), std::runtime_error);
}

// With light subpaths guided (--guide-light) the importance field follows
// the radiance field's bytes: both come back bit for bit, a field restored
// into a render that guides other subpaths is refused, and so are bytes
// cut inside the importance field.
TEST(Guiding, BothFieldsBytesRoundTrip) {
  const Vec3 lo(-1.f), hi(2.f);
  GuidingField field(lo, hi, 64, true, true);
  std::mt19937 rng(9);
  std::uniform_real_distribution<float> u(0.f, 1.f);
  auto records = [&](const SDTree& tree, float scale) {
    std::vector<GuideRecord> out;
    for (int i = 0; i < 20000; ++i) {
      const Vec3 p = lo + (hi - lo) * Vec3(u(rng), u(rng), u(rng)) * Vec3(scale, 1.f, 1.f);
      GuideRecord r{};
      r.leaf = tree.leaf_of(p);
      r.bin = uint8_t(i % SDTree::kBins);
      r.cell =
          tree.leaf(r.leaf).learning[r.bin].cell_of(equal_area_square_to_sphere(Vec2(u(rng), 0.2f + 0.5f * u(rng))));
      r.energy = 1.f + u(rng);
      r.second = r.energy, r.bsdf_pdf = 0.3f, r.guide_pdf = -1.f;
      out.push_back(r);
    }
    return out;
  };
  for (int iteration = 0; iteration < 3; ++iteration) {
    // (the importance records crowd into a third of the box: the two trees split differently)
    const std::vector<GuideRecord> eye = records(field.tree(), 1.f), light = records(field.importance_tree(), 0.33f);
    field.deposit(eye, light);
    field.end_iteration();
  }
  ASSERT_GT(field.importance_tree().leaves().size(), 1u);
  ASSERT_NE(field.importance_tree().leaves().size(), field.tree().leaves().size());
  const std::string bytes = field.save();
  GuidingField restored(lo, hi, 64, true, true);
  restored.restore(bytes);
  EXPECT_EQ(restored.save(), bytes);
  EXPECT_EQ(restored.importance_tree().leaves().size(), field.importance_tree().leaves().size());
  for (const auto& [eye, light] : {std::pair{true, false}, std::pair{false, true}}) {
    GuidingField other(lo, hi, 64, eye, light);
    EXPECT_THROW(other.restore(bytes), std::runtime_error) << eye << light;
  }
  GuidingField cut(lo, hi, 64, true, true);
  EXPECT_THROW(cut.restore(bytes.substr(0, bytes.size() - 9)), std::runtime_error);
}

