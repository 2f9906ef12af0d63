#include "app/session_watcher.h"

#include <chrono>

#include "app/log.h"

namespace lantern {

SessionWatcher::SessionWatcher(Look look, double interval, double spacing)
    : look_(std::move(look)), interval_(interval), spacing_(spacing) {}

SessionWatcher::~SessionWatcher() { stop(); }

void SessionWatcher::watch(const RenderSession& session) {
  thread_ = std::thread([this, &session] {
    using Clock = std::chrono::steady_clock;
    const auto wait = interval_ > 0 ? std::chrono::duration<double>(interval_) : std::chrono::hours(24 * 365);
    auto last = Clock::now() - std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(spacing_));
    std::unique_lock<std::mutex> lock(mutex_);
    for (;;) {
      wake_.wait_for(lock, wait, [&] { return stopping_ || pass_ended_; });
      // A pass that ended is looked at even when the render ended right after.
      if (stopping_ && !pass_ended_) break;
      const bool timed_out = !pass_ended_;
      pass_ended_ = false;
      if (timed_out && interval_ <= 0) continue;
      const auto now = Clock::now();
      if (std::chrono::duration<double>(now - last).count() < spacing_) continue;
      last = now;
      const uint32_t spp = spp_;
      lock.unlock();
      try {
        look_(session.snapshot(), spp);
      } catch (const std::exception& e) {
        // (A film too large to copy once more, an image that cannot be
        // written.) The render goes on without this look; later ones may
        // succeed.
        if (!warned_) logging::warning("warning: while rendering: %s; the render goes on", e.what());
        warned_ = true;
      }
      lock.lock();
    }
  });
}

void SessionWatcher::pass_done(uint32_t spp) {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    pass_ended_ = true;
    spp_ = spp;
  }
  wake_.notify_all();
}

void SessionWatcher::stop() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stopping_ = true;
  }
  wake_.notify_all();
  if (thread_.joinable()) thread_.join();
}

}  // namespace lantern
