// Checkpoints in pieces, as MPI ranks write them (FILE.rank<r>), made here
// by renders in one process that share out the units with tickets: any
// stop, resumed by one process reading every piece, ends with the image of
// a straight render, bit for bit; a piece another holds entirely is
// skipped; pieces that share only some units are refused.
#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <functional>

#include "film/checkpoint.h"
#include "lantern/render.h"
#include "lantern/scene.h"
#include "same_image.h"

namespace lantern {
namespace {

std::string pieces_base() {
  const ::testing::TestInfo* t = ::testing::UnitTest::GetInstance()->current_test_info();
  return ::testing::TempDir() + "/lantern_pieces_" + t->name() + ".ckpt";
}

void remove_pieces(const std::string& base) {
  for (const std::string& p : checkpoint_pieces(base)) std::filesystem::remove(p);
}

RenderOptions pieces_render() {
  RenderOptions o;
  o.integrator = Integrator::Bdpt;
  o.spp = 40;
  o.width = 40;
  o.height = 30;
  o.maxdepth = 5;
  o.wave_size = 256;
  o.seed = 11;
  return o;
}

// A "rank" of a job of `ranks`: takes the runs of four tickets r, r + ranks,
// ... and stops after `checkpoints` checkpoints, written as piece r (or
// file_rank).
RenderResult render_rank(const Scene& scene, RenderOptions o, const std::string& base, int r, int ranks,
                         int checkpoints, int file_rank = -1) {
  std::atomic<bool> cancel{false};
  int written = 0;
  uint64_t run = uint64_t(r), left = 0, ticket = 0;
  RenderHooks hooks;
  hooks.next_ticket = [&]() -> uint64_t {
    if (left == 0) {
      ticket = 4 * run;
      run += uint64_t(ranks);
      left = 4;
    }
    --left;
    return ticket++;
  };
  o.checkpoint_path = base;
  o.checkpoint_rank = file_rank >= 0 ? file_rank : r;
  o.resume_reads = false;  // as a rank other than 0: leaves the others' pieces alone
  o.checkpoint_seconds = 1e-9;
  hooks.cancel = &cancel;
  hooks.checkpoint_written = [&] {
    if (++written == checkpoints) cancel = true;
  };
  return render(scene, o, hooks);
}

TEST(CheckpointPieces, StoppedRanksResumedByOneProcess) {
  auto scene = load_scene(std::string(LANTERN_SOURCE_DIR) + "/scenes/cornell-box.pbrt");
  const RenderOptions o = pieces_render();
  const RenderResult straight = render(*scene, o);
  const std::string base = pieces_base();
  remove_pieces(base);
  EXPECT_TRUE(render_rank(*scene, o, base, 0, 2, 3).interrupted);
  EXPECT_TRUE(render_rank(*scene, o, base, 1, 2, 5).interrupted);
  ASSERT_EQ(checkpoint_pieces(base).size(), 2u);

  // One process resumes, is stopped once more (it saves every piece as its
  // own first and removes the others), and resumes to the end.
  RenderOptions resume = o;
  resume.checkpoint_path = base;
  resume.checkpoint_seconds = 1e-9;
  resume.resume = true;
  std::atomic<bool> cancel{false};
  RenderHooks hooks;
  hooks.cancel = &cancel;
  int written = 0;
  hooks.checkpoint_written = [&] {
    if (++written == 4) cancel = true;
  };
  EXPECT_TRUE(render(*scene, resume, hooks).interrupted);
  EXPECT_EQ(checkpoint_pieces(base), std::vector<std::string>{base});
  const RenderResult resumed = render(*scene, resume);
  EXPECT_FALSE(resumed.interrupted);
  EXPECT_EQ(resumed.stats.samples, straight.stats.samples);
  EXPECT_TRUE(same_image(resumed.image, straight.image)) << "the resumed image differs from the straight one";
  EXPECT_TRUE(checkpoint_pieces(base).empty()) << "a finished render leaves no piece";
}

TEST(CheckpointPieces, AbsorbedPiecesAreSkippedPartialOverlapsRefused) {
  auto scene = load_scene(std::string(LANTERN_SOURCE_DIR) + "/scenes/cornell-box.pbrt");
  const RenderOptions o = pieces_render();
  const RenderResult straight = render(*scene, o);
  const std::string base = pieces_base();
  remove_pieces(base);
  render_rank(*scene, o, base, 0, 2, 2);
  render_rank(*scene, o, base, 1, 2, 2);
  const std::string rank1 = base + ".rank1", saved = base + ".saved";
  std::filesystem::copy_file(rank1, saved, std::filesystem::copy_options::overwrite_existing);

  // A resumed process takes both in, saves them and is stopped; the old
  // rank 1 piece put back is held entirely by the new piece: skipped.
  RenderOptions resume = o;
  resume.checkpoint_path = base;
  resume.checkpoint_seconds = 1e-9;
  resume.resume = true;
  std::atomic<bool> cancel{false};
  RenderHooks hooks;
  hooks.cancel = &cancel;
  hooks.checkpoint_written = [&] { cancel = true; };
  EXPECT_TRUE(render(*scene, resume, hooks).interrupted);
  std::filesystem::copy_file(saved, rank1, std::filesystem::copy_options::overwrite_existing);
  EXPECT_TRUE(same_image(render(*scene, resume).image, straight.image)) << "a piece was counted twice";

  // Pieces of two different splits of the same render share some units
  // but not all: refused, naming both. Rank 1 of 2 takes tickets 4-7,
  // 12-15, ...; rank 1 of 3 takes 4-7, 16-19, ...
  remove_pieces(base);
  render_rank(*scene, o, base, 1, 2, 6, 0);
  render_rank(*scene, o, base, 1, 3, 9, 1);
  try {
    render(*scene, resume);
    ADD_FAILURE() << "overlapping pieces were accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("do not fit together"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find(".ckpt.rank1"), std::string::npos) << e.what();
  }
  remove_pieces(base);
  std::filesystem::remove(saved);
}

}  // namespace
}  // namespace lantern
