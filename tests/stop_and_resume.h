// A render stopped and resumed until it finishes: stopped after a
// different number of checkpoints in each run (first_stop, then step more
// each run; a checkpoint after every wave), on 1 and 2 threads in turn.
#pragma once

#include <gtest/gtest.h>

#include <atomic>
#include <cstdio>
#include <cstring>
#include <functional>
#include <string>

#include "lantern/render.h"
#include "lantern/scene.h"

namespace lantern {

inline RenderResult render_stopped_and_resumed(const Scene& scene, RenderOptions o, const std::string& checkpoint,
                                               int first_stop, int step, int* runs,
                                               const std::function<void(const RenderResult&)>& interrupted = {}) {
  std::remove(checkpoint.c_str());
  o.checkpoint_path = checkpoint;
  o.checkpoint_seconds = 1e-9;  // after every wave
  std::atomic<bool> cancel{false};
  int written = 0, stop_after = 0;
  RenderHooks hooks;
  hooks.cancel = &cancel;
  hooks.checkpoint_written = [&] {
    if (++written == stop_after) cancel = true;
  };
  RenderResult r;
  *runs = 0;
  do {
    written = 0;
    cancel = false;
    o.threads = 1 + *runs % 2;
    stop_after = first_stop + step * *runs;
    r = render(scene, o, hooks);
    o.resume = true;
    if (++*runs >= 60) {
      ADD_FAILURE() << "never finished";
      break;
    }
    if (r.interrupted && interrupted) interrupted(r);
  } while (r.interrupted);
  return r;
}

// The render of `o`, stopped and resumed (as above) at least `min_runs`
// times, ends on the image of a render that ran straight through, bit for
// bit, with as many samples.
inline void expect_resumes_to_the_straight_image(const Scene& scene, const RenderOptions& o, const char* name,
                                                 int first_stop, int step, int min_runs, const std::string& what = "") {
  const RenderResult straight = render(scene, o);
  const std::string checkpoint = ::testing::TempDir() + "/" + name;
  int runs = 0;
  const RenderResult r = render_stopped_and_resumed(scene, o, checkpoint, first_stop, step, &runs);
  EXPECT_GE(runs, min_runs) << what;
  EXPECT_EQ(r.stats.samples, straight.stats.samples) << what;
  EXPECT_EQ(0, std::memcmp(r.image.rgb.data(), straight.image.rgb.data(), r.image.rgb.size() * sizeof(float))) << what;
  std::remove(checkpoint.c_str());
}

}  // namespace lantern
