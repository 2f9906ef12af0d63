// The one door every integrator uses to trace rays: whole batches, never a
// single ray from inside shading code. The back end is a run-time switch so
// benchmarks can compare Embree's stream, single-ray and packet interfaces on
// the very same batches.
#pragma once

#include <embree3/rtcore.h>

#include <array>
#include <atomic>
#include <string>
#include <vector>

#include "accel/ray_batch.h"
#include "entity/shapes.h"
#include "lantern/options.h"
#include "trace/trace_buffer.h"

namespace lantern {

enum class RayKind { Camera, Extension, LightExtension, Shadow };

struct RayCounters {
  std::atomic<uint64_t> camera{0}, extension{0}, light{0}, shadow{0};
};

class RayStream {
 public:
  RayStream(RTCScene scene, RayBackend backend, RayCounters* counters);

  // Closest hits for all rays of the batch. With instances set, a hit on
  // instance k leaves geom_id = the pool index of the prototype geometry
  // hit and inst_id = k; other hits keep inst_id invalid.
  void intersect(RayBatch& batch, RayKind kind);
  // With the scene's pools set, hits come back as shading reads them:
  // instance hits as above, and hits on a mesh Embree traces as quads as
  // the triangle and barycentrics of the same point.
  void set_scene(uint32_t instance_base, const ShapePools* shapes) {
    instance_base_ = instance_base;
    shapes_ = shapes;
    has_instances_ = shapes && !shapes->instances.empty();
    has_quads_ = false;
    if (shapes)
      for (const TriangleMesh& m : shapes->meshes) has_quads_ = has_quads_ || !m.quads.empty();
  }
  // Any hit: afterwards batch.occluded(i) says whether ray i was blocked.
  void occluded(RayBatch& batch);

  // Wall time spent in Embree queries by this stream, per RayKind; kept
  // only when timing is on (a clock read per batch, not per ray).
  void set_timing(bool on) { timing_ = on; }
  // Every batch is also written here before it is queried (`--dump-rays`).
  void set_dump(class RayDump* dump) { dump_ = dump; }
  // Each query also becomes a span on this track (--trace), with the
  // paths-alive and rays-per-query counters; null: none.
  void set_trace(class TraceBuffer* trace) { trace_ = trace; }
  const std::array<double, 4>& seconds() const { return seconds_; }

 private:
  void run_intersect(RayBatch& batch, RayKind kind);
  void run_occluded(RayBatch& batch);

  void remap_instance_hits(RayBatch& batch) const;
  void remap_quad_hits(RayBatch& batch) const;
  void record(RayKind kind, uint32_t count, TraceClock::time_point t0, TraceClock::time_point t1);

  RTCScene scene_;
  uint32_t instance_base_ = 0;
  const ShapePools* shapes_ = nullptr;  // with instances or quads: hits are rewritten
  bool has_instances_ = false, has_quads_ = false;
  RayBackend backend_;
  RayCounters* counters_;
  std::vector<RTCRayHit> aos_;   // scratch for the 1M back end
  std::vector<RTCRay> aos_rays_;
  bool timing_ = false;
  class RayDump* dump_ = nullptr;
  class TraceBuffer* trace_ = nullptr;
  std::array<double, 4> seconds_{};
};

}  // namespace lantern
