// Looking at a render while it runs: a thread of its own takes the image
// of the passes so far (RenderSession::snapshot) after each pass, and, if
// asked, every so many seconds between passes, and hands it on (a display
// server, a partial image file). The render never waits for it: passes
// that end while it is busy are looked at once, when it is free.
#pragma once

#include <condition_variable>
#include <cstdint>
#include <functional>
#include <mutex>
#include <thread>

#include "lantern/render.h"

namespace lantern {

class SessionWatcher {
 public:
  // look(image, spp): spp is the last pass's samples per pixel (0 before
  // the first pass ends). Between passes every `interval` seconds (0:
  // after passes only); no two looks closer than `spacing` seconds (0: as
  // often as passes end).
  using Look = std::function<void(const Image& image, uint32_t spp)>;
  SessionWatcher(Look look, double interval, double spacing);
  ~SessionWatcher();  // stop()
  SessionWatcher(const SessionWatcher&) = delete;
  SessionWatcher& operator=(const SessionWatcher&) = delete;

  // Starts looking at `session` (which must outlive the watcher or stop()).
  void watch(const RenderSession& session);
  // From RenderHooks::pass_done.
  void pass_done(uint32_t spp);
  // Ends the thread; a pass that ended and was not looked at yet is, unless
  // it comes within `spacing` of the last look.
  void stop();

 private:
  Look look_;
  double interval_, spacing_;
  std::thread thread_;
  std::mutex mutex_;
  std::condition_variable wake_;
  bool stopping_ = false, pass_ended_ = false, warned_ = false;
  uint32_t spp_ = 0;
};

}  // namespace lantern
