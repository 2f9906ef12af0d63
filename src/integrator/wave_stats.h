// What a thread's waves measure about themselves: time per stage and how
// subpaths end. Plain per-thread counters (no atomics); the renderer sums
// them over threads at the end. With timing off a StageTimer reads no clock.
#pragma once

#include <algorithm>
#include <array>
#include <chrono>
#include <cstdint>

#include "trace/trace_buffer.h"

namespace lantern {

// CPU stages of a wave, outside the ray queries (which RayStream times).
enum class Stage : uint8_t {
  Generate,    // camera rays, light emission
  Surface,     // hit reconstruction, emission found by eye subpaths, binning
  Shade,       // per vertex: next-event estimation, connections, light tracing, merges; then the next direction
  Accumulate,  // adding unoccluded contributions, splat records
  Count
};
inline constexpr int kStageCount = int(Stage::Count);
inline const char* stage_name(Stage s) {
  static const char* names[] = {"generate", "surface", "shade", "accumulate"};
  return names[int(s)];
}

// Why a subpath ended.
enum class PathEnd : uint8_t { Escaped, Absorbed, Roulette, MaxDepth, Count };
inline constexpr int kPathEndCount = int(PathEnd::Count);
inline const char* path_end_name(PathEnd e) {
  static const char* names[] = {"escaped", "absorbed", "roulette", "maxdepth"};
  return names[int(e)];
}

struct WaveStats {
  bool timing = false;
  TraceBuffer* trace = nullptr;  // with --trace: this thread's track
  std::array<double, kStageCount> seconds{};
  uint64_t eye_vertices = 0, light_vertices = 0;  // surface hits of each kind of subpath
  std::array<uint64_t, kPathEndCount> eye_ends{}, light_ends{};
  // Next-event estimation (the path tracer's, bdpt's s = 1): lights sampled,
  // and those whose sample was non-zero and unoccluded.
  uint64_t light_samples = 0, light_samples_unoccluded = 0;
  uint64_t light_connections = 0;  // bdpt: shadow rays of strategies with s >= 2 (the cost the light subpath rate scales)
  uint64_t camera_connections = 0;  // of those, t = 1's: a light subpath's vertices joined to the camera
  uint64_t merges = 0;  // vcm: light vertices merged
  double grid_seconds = 0.0;   // vcm, with timing: building the merging grids
  uint32_t last_pass = 0;      // vcm: the largest first sample index of a wave traced

  void operator+=(const WaveStats& o) {
    merges += o.merges;
    grid_seconds += o.grid_seconds;
    last_pass = std::max(last_pass, o.last_pass);
    for (int i = 0; i < kStageCount; ++i) seconds[size_t(i)] += o.seconds[size_t(i)];
    eye_vertices += o.eye_vertices;
    light_vertices += o.light_vertices;
    light_samples += o.light_samples;
    light_samples_unoccluded += o.light_samples_unoccluded;
    light_connections += o.light_connections;
    camera_connections += o.camera_connections;
    for (int i = 0; i < kPathEndCount; ++i) {
      eye_ends[size_t(i)] += o.eye_ends[size_t(i)];
      light_ends[size_t(i)] += o.light_ends[size_t(i)];
    }
  }
};

// Times a stage for --stats and records it as a span for --trace; reads no
// clock when neither is on.
class StageTimer {
 public:
  StageTimer(WaveStats& s, Stage stage) : stats_(s), stage_(stage) {
    if (s.timing || s.trace) start_ = TraceClock::now();
  }
  ~StageTimer() {
    if (!stats_.timing && !stats_.trace) return;
    const TraceClock::time_point end = TraceClock::now();
    if (stats_.timing) stats_.seconds[size_t(stage_)] += std::chrono::duration<double>(end - start_).count();
    if (stats_.trace) stats_.trace->span(stage_name(stage_), TraceCategory::Stage, start_, end);
  }
  StageTimer(const StageTimer&) = delete;
  StageTimer& operator=(const StageTimer&) = delete;

 private:
  WaveStats& stats_;
  Stage stage_;
  TraceClock::time_point start_;
};

}  // namespace lantern
