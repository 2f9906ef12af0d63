// Recording the ray batches a render hands to Embree (`--dump-rays`), so a
// micro-benchmark can replay exactly those rays against Embree alone, and
// the count of rays can be checked against the render's own counters.
// Format: per batch, uint32 kind (RayKind), uint32 count, then count records
// of 8 floats: origin xyz, direction xyz, tnear, tfar.
#pragma once

#include <cstdio>
#include <mutex>
#include <string>
#include <vector>

#include "accel/ray_batch.h"

namespace lantern {

enum class RayKind;

class RayDump {
 public:
  explicit RayDump(const std::string& path);  // throws std::runtime_error
  ~RayDump();
  RayDump(const RayDump&) = delete;
  RayDump& operator=(const RayDump&) = delete;
  // Thread-safe: batches of different threads interleave whole.
  void write(RayKind kind, const RayBatch& batch);

 private:
  std::mutex mutex_;
  std::FILE* file_ = nullptr;
  std::vector<float> buffer_;
};

struct DumpedBatch {
  uint32_t kind;
  RayBatch rays;
};
// Throws std::runtime_error for a missing or truncated file.
std::vector<DumpedBatch> read_ray_dump(const std::string& path);

}  // namespace lantern
