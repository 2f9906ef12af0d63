// RenderSession: what a viewer or a script sees of a render while it runs.
// The image at the end of each pass is the image of a render with that
// many samples, bit for bit; a started render can be watched, cancelled
// and waited for; a session runs once.
#include <gtest/gtest.h>

#include <chrono>
#include <cstring>
#include <stdexcept>
#include <thread>

#include "lantern/render.h"
#include "lantern/scene.h"
#include "same_image.h"

namespace lantern {
namespace {

RenderOptions session_render(Integrator integrator, int spp) {
  RenderOptions o;
  o.integrator = integrator;
  o.spp = spp;
  o.width = 40;
  o.height = 30;
  o.wave_size = 256;
  o.seed = 3;
  o.threads = 2;
  // A sampler whose samples do not depend on the planned count, so that
  // the first 16 samples of a 48-sample render are those of a 16-sample one.
  o.sampler.type = SamplerKind::Independent;
  return o;
}

double mean(const Image& im) {
  double s = 0;
  for (float v : im.rgb) s += v;
  return im.rgb.empty() ? 0.0 : s / double(im.rgb.size());
}

class SessionPasses : public ::testing::TestWithParam<Integrator> {};

// Passes of 16 samples: the snapshot taken when each ends equals a render
// of 16, 32 and 48 samples (path, and bdpt with its light-tracing splats).
TEST_P(SessionPasses, EachPassShowsTheRenderOfItsSamples) {
  auto scene = load_scene(std::string(LANTERN_SOURCE_DIR) + "/scenes/cornell-box.pbrt");
  std::vector<uint32_t> spps;
  std::vector<Image> snapshots;
  RenderSession* session_ptr = nullptr;
  RenderHooks hooks;
  hooks.pass_done = [&](uint32_t spp) {
    spps.push_back(spp);
    snapshots.push_back(session_ptr->snapshot());
  };
  RenderSession session(*scene, session_render(GetParam(), 48), hooks);
  session_ptr = &session;
  const RenderResult whole = session.run();
  ASSERT_EQ(spps, (std::vector<uint32_t>{16, 32, 48}));
  EXPECT_TRUE(same_image(snapshots.back(), whole.image));
  for (size_t k = 0; k < 2; ++k) {
    const RenderResult shorter = render(*scene, session_render(GetParam(), int(spps[k])));
    EXPECT_TRUE(same_image(snapshots[k], shorter.image)) << "after pass " << k + 1;
  }
  // The passes differ, so the equalities above say something.
  EXPECT_FALSE(same_image(snapshots[0], snapshots[1]));
}

INSTANTIATE_TEST_SUITE_P(Integrators, SessionPasses, ::testing::Values(Integrator::Path, Integrator::Bdpt));

TEST(Session, AStartedRenderIsWatchedCancelledAndWaitedFor) {
  auto scene = load_scene(std::string(LANTERN_SOURCE_DIR) + "/scenes/cornell-box.pbrt");
  RenderSession session(*scene, session_render(Integrator::Path, 1 << 20));
  EXPECT_EQ(session.width(), 40);
  EXPECT_EQ(session.height(), 30);
  EXPECT_EQ(mean(session.snapshot()), 0.0) << "nothing rendered yet";
  session.start();
  const auto give_up = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  while (session.progress().samples_done < 40 * 30 * 16 && std::chrono::steady_clock::now() < give_up)
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  const Image partial = session.snapshot();
  EXPECT_GT(mean(partial), 0.0);
  const RenderProgress p = session.progress();
  EXPECT_GT(p.samples_done, 0u);
  EXPECT_LT(p.fraction, 1.0);
  session.cancel();
  const RenderResult r = session.wait();
  EXPECT_TRUE(r.interrupted);
  EXPECT_GE(r.stats.samples, p.samples_done);
  EXPECT_LT(r.stats.samples, uint64_t(40 * 30) << 20);
  EXPECT_THROW(session.run(), std::logic_error) << "a session runs once";
}

TEST(Session, BadOptionsAreRefusedWhenTheSessionIsMade) {
  auto scene = load_scene(std::string(LANTERN_SOURCE_DIR) + "/scenes/cornell-box.pbrt");
  RenderOptions o = session_render(Integrator::Path, 4);
  o.maxdepth = -1;
  EXPECT_THROW(RenderSession(*scene, o), std::invalid_argument);
}

TEST(Session, ASessionDestroyedWhileRenderingStopsIt) {
  auto scene = load_scene(std::string(LANTERN_SOURCE_DIR) + "/scenes/cornell-box.pbrt");
  const auto t0 = std::chrono::steady_clock::now();
  {
    RenderSession session(*scene, session_render(Integrator::Bdpt, 1 << 20));
    session.start();
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  EXPECT_LT(std::chrono::steady_clock::now() - t0, std::chrono::seconds(60));
}

}  // namespace
}  // namespace lantern
