// A timeline of a render for profilers (`--trace FILE.json`): every wave,
// the stages and ray queries inside it, the serial film merge, loading and
// writing, as spans on one track per thread, plus counters (paths alive,
// rays per query, waves waiting for the film merge). Written in Chrome's
// trace-event format, which Perfetto and chrome://tracing open.
//
// Each thread appends to a buffer of its own (no locks, no atomics on the
// way); the file is assembled at the end. Times come from one monotonic
// clock (steady_clock), as offsets from the timeline's creation. With no
// timeline the integrators read no clock: the stage timers and ray streams
// test one pointer per stage or batch.
#pragma once

#include <tbb/enumerable_thread_specific.h>

#include <atomic>
#include <deque>
#include <mutex>
#include <string>

#include "trace/trace_buffer.h"

namespace lantern {

class Timeline {
 public:
  // Waves numbered below full_waves are kept in full; later ones leave
  // only their counters. 0 keeps every wave.
  explicit Timeline(uint64_t full_waves = 0);

  TraceBuffer& local();                          // the calling thread's track (a worker's)
  TraceBuffer& main() { return main_; }          // the main thread's: load, render, write
  TraceBuffer& pipeline() { return pipeline_; }  // the pipeline's serial stage (film merge)

  bool keeps(int64_t wave) const { return full_waves_ == 0 || wave < int64_t(full_waves_); }
  int64_t ns(TraceClock::time_point t) const {
    return std::chrono::duration_cast<std::chrono::nanoseconds>(t - origin_).count();
  }
  // A name that lives as long as the timeline (for spans named at run time).
  const char* intern(const std::string& name);
  // Waves traced but not merged into the film yet.
  std::atomic<int64_t>& merge_queue() { return merge_queue_; }

  // The whole timeline as trace-event JSON.
  std::string json() const;

 private:
  TraceClock::time_point origin_;
  uint64_t full_waves_;
  std::atomic<uint32_t> next_track_{2};
  std::mutex names_mutex_;
  std::deque<std::string> names_;  // before the buffers, which intern their counters' names
  std::atomic<int64_t> merge_queue_{0};
  TraceBuffer main_, pipeline_;
  tbb::enumerable_thread_specific<TraceBuffer> workers_;
};

}  // namespace lantern
