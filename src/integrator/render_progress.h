// How far a render is, for the progress hook: reported twice a second from
// a thread of its own, and once at the end.
#pragma once

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <mutex>
#include <thread>

#include "lantern/render.h"

namespace lantern {

using Clock = std::chrono::steady_clock;

// The progress of a render that began at `start`.
inline RenderProgress progress_at(const RenderOptions& o, Clock::time_point start, uint64_t done, uint64_t total) {
  RenderProgress p;
  p.elapsed_seconds = std::chrono::duration<double>(Clock::now() - start).count();
  p.samples_done = done;
  p.samples_total = total;
  p.fraction = o.time_limit_seconds > 0 ? std::min(1.0, p.elapsed_seconds / o.time_limit_seconds)
                                        : double(p.samples_done) / double(std::max<uint64_t>(total, 1));
  return p;
}

// Calls the progress hook twice a second from its own thread, and once at
// the end.
class ProgressReporter {
 public:
  ProgressReporter(const RenderOptions& o, const RenderHooks& hooks, Clock::time_point start,
                   const std::atomic<uint64_t>& done, uint64_t total)
      : opts_(o), hooks_(hooks), start_(start), done_(done), total_(total) {
    if (hooks.progress) thread_ = std::thread([this] { loop(); });
  }
  ~ProgressReporter() {
    {
      std::lock_guard<std::mutex> l(m_);
      stop_ = true;
    }
    cv_.notify_all();
    if (thread_.joinable()) thread_.join();
    if (hooks_.progress) hooks_.progress(snapshot());
  }

 private:
  RenderProgress snapshot() const { return progress_at(opts_, start_, done_.load(), total_); }
  void loop() {
    std::unique_lock<std::mutex> l(m_);
    while (!cv_.wait_for(l, std::chrono::milliseconds(500), [this] { return stop_; })) hooks_.progress(snapshot());
  }
  const RenderOptions& opts_;
  const RenderHooks& hooks_;
  Clock::time_point start_;
  const std::atomic<uint64_t>& done_;
  uint64_t total_;
  std::mutex m_;
  std::condition_variable cv_;
  bool stop_ = false;
  std::thread thread_;
};

}  // namespace lantern
