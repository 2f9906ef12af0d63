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
#include <chrono>
#include <cstdint>
#include <deque>
#include <mutex>
#include <string>
#include <vector>

namespace lantern {

using TraceClock = std::chrono::steady_clock;

enum class TraceCategory : uint8_t { Wave, Stage, Rays, Pipeline, Load, Render, Output };

struct TraceEvent {
  const char* name;  // a static string, or one the timeline keeps
  TraceCategory category;
  char phase;  // 'X': a span; 'C': a counter sample
  int64_t begin_ns, duration_ns;
  int64_t wave;   // the wave's number in the render, or -1
  int64_t value;  // rays in a query, or the counter's value; -1: none
};

class Timeline;

// One thread's track.
class TraceBuffer {
 public:
  TraceBuffer(Timeline* owner, uint32_t track, std::string name);

  // The wave this thread works on from now on: its spans are kept when the
  // timeline keeps that wave in full (counters always are).
  void begin_wave(int64_t wave);
  void end_wave() { wave_ = -1, full_ = true; }
  int64_t wave() const { return wave_; }

  void span(const char* name, TraceCategory category, TraceClock::time_point begin, TraceClock::time_point end,
            int64_t value = -1);
  // A counter sample; `always`: kept for waves not kept in full too.
  void counter(const char* name, TraceClock::time_point at, int64_t value, bool always = false);

  // This track's own counters: the paths alive in its wave, and the rays of
  // its latest query (counter tracks are per name, so each thread's carry
  // the thread's name).
  const char* paths_alive_name() const { return paths_alive_; }
  const char* rays_per_query_name() const { return rays_per_query_; }

  uint32_t track() const { return track_; }
  const std::string& name() const { return name_; }
  const std::vector<TraceEvent>& events() const { return events_; }
  uint64_t dropped_spans() const { return dropped_; }
  uint64_t dropped_waves() const { return dropped_waves_; }

 private:
  const Timeline* owner_;
  uint32_t track_;
  std::string name_;
  const char* paths_alive_ = "";
  const char* rays_per_query_ = "";
  int64_t wave_ = -1;
  bool full_ = true;
  uint64_t dropped_ = 0, dropped_waves_ = 0;
  std::vector<TraceEvent> events_;
};

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

// A span on `buffer` from construction to destruction; nothing when
// buffer is null.
class TraceSpan {
 public:
  TraceSpan(TraceBuffer* buffer, const char* name, TraceCategory category, int64_t value = -1)
      : buffer_(buffer), name_(name), category_(category), value_(value) {
    if (buffer_) begin_ = TraceClock::now();
  }
  ~TraceSpan() {
    if (buffer_) buffer_->span(name_, category_, begin_, TraceClock::now(), value_);
  }
  TraceSpan(const TraceSpan&) = delete;
  TraceSpan& operator=(const TraceSpan&) = delete;

 private:
  TraceBuffer* buffer_;
  const char* name_;
  TraceCategory category_;
  int64_t value_;
  TraceClock::time_point begin_;
};

}  // namespace lantern
