// One thread's track of a render timeline (trace/timeline.h): the spans and
// counters it records, with no locks. The stage timers and ray streams
// include only this.
#pragma once

#include <chrono>
#include <cstdint>
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
