// Checkpoints: a render stopped any number of times and resumed, on any
// thread count, ends bit for bit where a straight render ends; a checkpoint
// that does not belong to the render, or is damaged, is refused by name.
#include <gtest/gtest.h>

#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <tuple>
#include <utility>

#include "film/checkpoint.h"
#include "lantern/render.h"
#include "lantern/scene.h"
#include "sanitizer.h"
#include "stop_and_resume.h"

namespace lantern {
namespace {

// A file per test: ctest runs tests in parallel processes.
std::string checkpoint_file() {
  const ::testing::TestInfo* t = ::testing::UnitTest::GetInstance()->current_test_info();
  std::string name = std::string(t->test_suite_name()) + "_" + t->name();
  for (char& c : name)
    if (c == '/') c = '_';
  return ::testing::TempDir() + "/lantern_" + name + ".ckpt";
}

RenderOptions small_render(const std::string& integrator, const std::string& sampler = "zsobol") {
  RenderOptions o;
  o.integrator = parse_integrator(integrator);
  o.sampler.type = parse_sampler(sampler);
  o.spp = 40;  // three passes of up to 16
  o.width = 48;
  o.height = 36;
  o.maxdepth = 6;
  o.wave_size = 512;  // many waves, so stops fall in the middle of passes
  o.seed = 7;
  return o;
}

bool same_bits(const Image& a, const Image& b) {
  return a.width == b.width && a.height == b.height &&
         std::memcmp(a.rgb.data(), b.rgb.data(), a.rgb.size() * sizeof(float)) == 0;
}

void expect_resumes_bit_for_bit(const std::string& integrator, const std::string& sampler,
                                const std::string& scene_file = "scenes/lantern.pbrt") {
  auto scene = load_scene(std::string(LANTERN_SOURCE_DIR) + "/" + scene_file);
  RenderResult straight = render(*scene, small_render(integrator, sampler));

  const std::string kCheckpoint = checkpoint_file();
  int runs = 0;
  const RenderResult r = render_stopped_and_resumed(*scene, small_render(integrator, sampler), kCheckpoint, 3, 5, &runs,
                                                    [&](const RenderResult& stopped) {
                                                      EXPECT_TRUE(std::filesystem::exists(kCheckpoint));
                                                      EXPECT_LT(stopped.stats.samples, straight.stats.samples);
                                                    });
  EXPECT_GE(runs, 3) << "the render should have been stopped at least twice";
  EXPECT_GT(r.resumed_samples, 0u);
  EXPECT_EQ(r.stats.samples, straight.stats.samples);
  EXPECT_EQ(r.stats.light_paths, straight.stats.light_paths);
  EXPECT_TRUE(same_bits(r.image, straight.image)) << "the resumed image differs from the straight one";
  EXPECT_FALSE(std::filesystem::exists(kCheckpoint)) << "a finished render leaves no checkpoint";
}

class CheckpointResume : public ::testing::TestWithParam<const char*> {};
TEST_P(CheckpointResume, StopsAndResumesBitForBit) { expect_resumes_bit_for_bit(GetParam(), "zsobol"); }
// Media add per-slot state (the medium each path is in) and deferred
// shadow weights; none of it may leak across waves or resumes.
TEST(CheckpointResumeMedia, StopsAndResumesBitForBit) {
  expect_resumes_bit_for_bit("path", "zsobol", "perf/media/fog-sphere.pbrt");
  expect_resumes_bit_for_bit("bdpt", "zsobol", "perf/media/smoke-grid.pbrt");
  // (vcm's waves in media are bdpt's with merging: the Release suite's.)
  if (!LANTERN_ASAN) expect_resumes_bit_for_bit("vcm", "zsobol", "perf/media/fog-sphere.pbrt");  // merges in the fog too
  // tracking draws its numbers from hashes of each segment, not from a
  // stream a resume would have to restore (the Release suite's check)
  if (!LANTERN_ASAN) expect_resumes_bit_for_bit("bdpt", "zsobol", "perf/media/cloud.pbrt");
}
INSTANTIATE_TEST_SUITE_P(Integrators, CheckpointResume, ::testing::Values("path", "bdpt", "lt", "vcm"));

// Every sampler's values depend only on (seed, pixel, index, dimension);
// these three find their indices in ways of their own (global sequences,
// rounds of strata). paddedsobol is built as zsobol is.
class CheckpointResumeSampler : public ::testing::TestWithParam<const char*> {};
TEST_P(CheckpointResumeSampler, StopsAndResumesBitForBit) {
  // What this adds to CheckpointResume is the samplers' purity, a property
  // of their arithmetic that the Release suite checks; the sanitized suite
  // runs the same checkpoint code through CheckpointResume.
  if (LANTERN_ASAN) GTEST_SKIP() << "covered by CheckpointResume under the sanitizers";
  expect_resumes_bit_for_bit("bdpt", GetParam());
}
INSTANTIATE_TEST_SUITE_P(Samplers, CheckpointResumeSampler, ::testing::Values("stratified", "halton", "sobol"));

// Makes a checkpoint by cancelling a render after its first wave.
void make_checkpoint(const Scene& scene, RenderOptions o) {
  std::atomic<bool> cancel{false};
  o.checkpoint_path = checkpoint_file();
  o.checkpoint_seconds = 1e-9;
  RenderHooks hooks;
  hooks.cancel = &cancel;
  hooks.checkpoint_written = [&] { cancel = true; };
  ASSERT_TRUE(render(scene, o, hooks).interrupted);
}

std::string resume_error(const Scene& scene, RenderOptions o) {
  const std::string kCheckpoint = checkpoint_file();
  o.checkpoint_path = kCheckpoint;
  o.resume = true;
  try {
    render(scene, o);
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(kCheckpoint), std::string::npos) << e.what();
    return e.what();
  }
  return "(no error)";
}

TEST(Checkpoint, RefusesACheckpointOfAnotherRender) {
  auto scene = load_scene(std::string(LANTERN_SOURCE_DIR) + "/scenes/cornell-box.pbrt");
  RenderOptions o = small_render("path");
  make_checkpoint(*scene, o);
  RenderOptions other = o;
  other.seed = 8;
  EXPECT_NE(resume_error(*scene, other).find("seed=7"), std::string::npos);
  other = o;
  other.integrator = Integrator::Bdpt;
  EXPECT_NE(resume_error(*scene, other).find("integrator=path"), std::string::npos);
  other = o;
  other.spp = 41;  // 40 = 16 + 16 + 8: the last pass is short
  EXPECT_NE(resume_error(*scene, other).find("budget spp 40"), std::string::npos);
  EXPECT_NE(resume_error(*scene, other).find("last pass is short"), std::string::npos);
  other = o;
  other.spp = 32;
  EXPECT_NE(resume_error(*scene, other).find("more than this render's 32"), std::string::npos);
  other = o;
  other.checkpoint_key = "another scene";
  EXPECT_NE(resume_error(*scene, other).find("another render"), std::string::npos);
  // The path tracer's roulette: named by its line, which a render at
  // pbrt-v4's rule does not have (the earlier checkpoints' fingerprint).
  other = o;
  other.roulette_scale = 1.f;
  const std::string e = resume_error(*scene, other);
  EXPECT_NE(e.find("made with \"roulette=2\" but this render has \"(no roulette line)\""), std::string::npos) << e;
  // bdpt's light subpath rate likewise: auto (the default) has its line,
  // rate 1 (pbrt-v4's bdpt, the earlier checkpoints') none.
  o = small_render("bdpt");
  make_checkpoint(*scene, o);
  other = o;
  other.light_subpath_rate = 1.f;
  const std::string b = resume_error(*scene, other);
  EXPECT_NE(b.find("made with \"light-subpaths=auto\" but this render has \"(no light-subpaths line)\""), std::string::npos)
      << b;
  other.light_subpath_rate = 0.5f;
  EXPECT_NE(resume_error(*scene, other).find("\"light-subpaths=0.5\""), std::string::npos);
}

// Fingerprints are compared by key: a line one side lacks is named as
// missing, not as a shift of every line after it.
TEST(Checkpoint, FingerprintDifferenceIsByKey) {
  EXPECT_EQ(fingerprint_difference("a=1\nb=2\n", "a=1\nr=2\nb=2\n"), std::make_pair(std::string("(no r line)"), std::string("r=2")));
  EXPECT_EQ(fingerprint_difference("a=1\nr=2\nb=2\n", "a=1\nb=2\n"), std::make_pair(std::string("r=2"), std::string("(no r line)")));
  EXPECT_EQ(fingerprint_difference("a=1\nb=2\n", "a=1\nb=3\n"), std::make_pair(std::string("b=2"), std::string("b=3")));
  EXPECT_EQ(fingerprint_difference("a=1\nb=2\n", "a=1\nb=2\n"), std::make_pair(std::string(), std::string()));
}

TEST(Checkpoint, RefusesDamagedAndMissingFiles) {
  auto scene = load_scene(std::string(LANTERN_SOURCE_DIR) + "/scenes/cornell-box.pbrt");
  RenderOptions o = small_render("path");
  const std::string kCheckpoint = checkpoint_file();
  std::remove(kCheckpoint.c_str());
  EXPECT_NE(resume_error(*scene, o).find("nothing to resume"), std::string::npos);

  make_checkpoint(*scene, o);
  std::string bytes;
  {
    std::ifstream in(kCheckpoint, std::ios::binary);
    bytes.assign(std::istreambuf_iterator<char>(in), {});
  }
  auto rewrite = [&](const std::string& b) { std::ofstream(kCheckpoint, std::ios::binary) << b; };
  std::string flipped = bytes;
  flipped[flipped.size() / 2] ^= 0x10;
  rewrite(flipped);
  EXPECT_NE(resume_error(*scene, o).find("checksum"), std::string::npos);
  rewrite(bytes.substr(0, bytes.size() - 100));
  EXPECT_NE(resume_error(*scene, o).find("truncated"), std::string::npos);
  rewrite("not a checkpoint at all");
  EXPECT_NE(resume_error(*scene, o).find("not a Lantern checkpoint"), std::string::npos);
  rewrite(bytes);
  o.checkpoint_path = kCheckpoint;
  o.resume = true;
  EXPECT_FALSE(render(*scene, o).interrupted);  // the intact file still resumes
}

// A finished render kept (keep_checkpoint) and resumed with a larger spp
// ends bit for bit where a straight render of that spp ends, when the
// samples allow: halton's sequence does not depend on the planned count;
// zsobol's does, through its power of two, so 48 extends to 64 (both 2^6)
// and 32 does not (and is refused, saying why).
RenderResult extended(const Scene& scene, RenderOptions o, uint32_t first_spp, const std::string& checkpoint) {
  std::remove(checkpoint.c_str());
  RenderOptions first = o;
  first.spp = int(first_spp);
  first.checkpoint_path = checkpoint;
  first.keep_checkpoint = true;
  EXPECT_FALSE(render(scene, first).interrupted);
  EXPECT_TRUE(std::filesystem::exists(checkpoint)) << "a kept checkpoint";
  o.checkpoint_path = checkpoint;
  o.resume = true;
  return render(scene, o);
}

TEST(CheckpointExtend, ALargerBudgetContinuesAFinishedRenderBitForBit) {
  auto scene = load_scene(std::string(LANTERN_SOURCE_DIR) + "/scenes/cornell-box.pbrt");
  const std::string kCheckpoint = checkpoint_file();
  // (Under the sanitizers bdpt's alone: the extension's code is the same
  // for all three; which samples continue which is the Release suite's.)
  std::vector<std::tuple<const char*, const char*, unsigned>> cases = {
      {"path", "halton", 32u}, {"bdpt", "zsobol", 48u}, {"vcm", "independent", 5u}};
  if (LANTERN_ASAN) cases = {{"bdpt", "zsobol", 48u}};
  for (const auto& [integrator, sampler, first] : cases) {
    RenderOptions o = small_render(integrator, sampler);
    o.spp = 64;
    // (vcm's merge pilot runs for 64 spp and not for 5: the extension goes
    // on as its checkpoint was made, with merges, where a straight render
    // may not merge; --merging on extends bit for bit)
    o.merging_pilot = false;
    const RenderResult straight = render(*scene, o);
    const RenderResult r = extended(*scene, o, first, kCheckpoint);
    EXPECT_EQ(r.resumed_samples, uint64_t(first) * 48 * 36) << integrator;
    EXPECT_EQ(r.stats.samples, straight.stats.samples) << integrator;
    EXPECT_TRUE(same_bits(r.image, straight.image)) << integrator << " " << sampler << " from " << first << " spp";
    EXPECT_FALSE(std::filesystem::exists(kCheckpoint)) << "the extension completed and kept nothing";
  }
  // zsobol from 32 (a block of 2^5 per pixel) to 64 (2^6): refused.
  RenderOptions o = small_render("path", "zsobol");
  o.spp = 32;
  o.checkpoint_path = kCheckpoint;
  o.keep_checkpoint = true;
  render(*scene, o);
  o.keep_checkpoint = false;
  o.spp = 64;
  const std::string why = resume_error(*scene, o);
  EXPECT_NE(why.find("zsobol sampler lays out"), std::string::npos) << why;
  EXPECT_NE(why.find("at most 32 spp"), std::string::npos) << why;
}

}  // namespace
}  // namespace lantern
