// A render stopped and resumed until it finishes: stopped after a
// different number of checkpoints in each run (first_stop, then step more
// each run; a checkpoint after every wave), on 1 and 2 threads in turn.
#pragma once

#include <gtest/gtest.h>

#include <atomic>
#include <cstdio>
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

}  // namespace lantern
