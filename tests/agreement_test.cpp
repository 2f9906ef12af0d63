// The processes of one image make one choice (integrator/agreement.h,
// RenderHooks::agree): where a pilot chooses, the choice the hook hands
// back is the one rendered, whatever this process's own pilot said. Under
// MPI the hook broadcasts rank 0's bytes (tests/mpi_test.cmake renders
// with it); here a hook plays rank 0.
#include "integrator/agreement.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "integrator/light_subpath_rate.h"
#include "integrator/render_settings.h"
#include "integrator/split_choice.h"
#include "lantern/scene.h"
#include "light/light_sampler.h"
#include "scene/scene.h"

using namespace lantern;

namespace {

// A hook that says `value` at its `at`-th call and leaves the others'
// bytes as they are; counts its calls.
template <class T>
RenderHooks saying(T value, int at, int* calls) {
  RenderHooks h;
  h.agree = [value, at, calls](std::string& choice) {
    if ((*calls)++ != at) return;
    StringWriter out;
    out.put(value);
    choice = out.bytes;
  };
  return h;
}

}  // namespace

TEST(Agreement, ValuesAndListsTakeTheAgreedBytes) {
  RenderHooks h;
  h.agree = [](std::string& choice) {
    StringWriter out;
    if (choice.size() == sizeof(float))
      out.put(0.3f);
    else
      out.put_vector(std::vector<float>{0.25f, 0.75f});
    choice = out.bytes;
  };
  float rate = 1.f;
  std::vector<float> light_choice{1.f};
  agree_on(h, rate);
  agree_on(h, light_choice);
  EXPECT_EQ(rate, 0.3f);
  EXPECT_EQ(light_choice, (std::vector<float>{0.25f, 0.75f}));
  // Without the hook (one process) a choice stays its own.
  agree_on(RenderHooks{}, rate);
  EXPECT_EQ(rate, 0.3f);
}

// bdpt's light subpath rate and the path tracer's split: their pilots run
// (or, for a render too small, do not), then the agreed choice is set.
// Dropping either agree_on call leaves the process's own choice, and the
// test fails.
TEST(Agreement, PilotsGiveWayToTheAgreedChoice) {
  const auto scene = load_scene(std::string(LANTERN_SOURCE_DIR) + "/scenes/cornell-box.pbrt");
  const LightSampler light_sampler(scene->lights, scene->shapes, scene->textures, LightSamplerKind::Bvh);
  RenderOptions o;
  o.integrator = Integrator::Bdpt;
  o.width = o.height = 64;
  o.spp = 256;  // (large enough for the rate pilot: nothing is rendered here)
  o.maxdepth = 5;
  const ImageRegion region = image_region(*scene, o);
  RenderStats stats;
  const PathTracerSettings eye_alone = path_settings(*scene, o, region, uint32_t(o.spp));
  BdptSettings own = bdpt_settings(*scene, o, region, uint32_t(o.spp)), told = own;
  set_light_subpath_rate(*scene, light_sampler, o, eye_alone, own, stats, RenderHooks{});
  int calls = 0;
  // (0.3 is no candidate of the pilot's: only the hook can say it)
  set_light_subpath_rate(*scene, light_sampler, o, eye_alone, told, stats, saying(0.3f, 0, &calls));
  EXPECT_NE(own.light_subpath_rate, 0.3f);
  EXPECT_EQ(told.light_subpath_rate, 0.3f);
  EXPECT_EQ(stats.light_subpath_rate, 0.3f) << "--stats reports the rate rendered";
  EXPECT_EQ(calls, 2) << "the rate, then the choice of light";

  o.spp = 16;
  PathTracerSettings path = path_settings(*scene, o, region, uint32_t(o.spp));
  calls = 0;
  set_split(*scene, light_sampler, o, path, stats, saying(uint32_t(4), 0, &calls));
  EXPECT_EQ(path.split, 4u) << "a render too small for the split pilot still takes the agreed split";
  EXPECT_EQ(calls, 1);
  BdptSettings small = bdpt_settings(*scene, o, region, uint32_t(o.spp));
  calls = 0;
  set_light_subpath_rate(*scene, light_sampler, o, eye_alone, small, stats, saying(0.3f, 0, &calls));
  EXPECT_EQ(small.light_subpath_rate, 0.3f) << "a render too small for the rate pilot still takes the agreed rate";
  EXPECT_EQ(calls, 2);
}
