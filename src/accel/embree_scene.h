// The Embree device and the scene built from the geometry pools: top-level
// geometries keep their pool index as Embree geomID; each instanced
// prototype is an Embree scene of its own, placed by Embree instance
// geometries or, compact, by one user geometry for all still instances
// (accel/instance_geometry.h).
#pragma once

#include <embree3/rtcore.h>

#include <atomic>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "accel/alpha_filter.h"
#include "accel/bilinear_geometry.h"
#include "accel/instance_geometry.h"
#include "accel/quadric_geometry.h"
#include "entity/shapes.h"
#include "lantern/options.h"

namespace lantern {

// MemoryLayout::Auto places instances compactly from this many still ones
// on, and builds Embree's compact BVH from this many primitives on
// (docs/performance.md, "Production scale").
inline constexpr size_t kCompactInstancesFrom = 100000;
inline constexpr size_t kCompactBvhFrom = 10000000;

class EmbreeScene {
 public:
  // The pools must outlive the scene: alpha filters and instances read them
  // while tracing.
  EmbreeScene(const ShapePools& shapes, const TexturePools& textures,
              MemoryLayout layout = MemoryLayout::Auto);  // throws std::runtime_error
  ~EmbreeScene();
  EmbreeScene(const EmbreeScene&) = delete;
  EmbreeScene& operator=(const EmbreeScene&) = delete;

  RTCScene handle() const { return scene_; }
  double build_seconds() const { return build_seconds_; }
  // Bytes Embree holds (BVH and its own buffers), as its memory monitor
  // reports them; shared geometry buffers belong to the scene's pools.
  int64_t bytes() const { return bytes_.load(); }
  int64_t peak_bytes() const { return peak_bytes_.load(); }
  // Bounds of everything in the scene.
  void bounds(Vec3* lo, Vec3* hi) const;
  // A hit on instance k reports instID[0] = instance_base() + k and the
  // geomID of the prototype's geometry within its own scene.
  uint32_t instance_base() const { return instance_base_; }
  bool compact_instances() const { return compact_ != nullptr; }
  bool compact_bvh() const { return compact_bvh_; }

 private:
  void attach(RTCScene scene, const ShapePools& shapes, uint32_t id, uint32_t embree_id);
  void build_prototypes(const ShapePools& shapes);
  void place_instances(const ShapePools& shapes, MemoryLayout layout);
  static void on_error(void* user, RTCError code, const char* str);
  static bool on_memory(void* user, ssize_t bytes, bool post);
  void check(const char* what);

  std::mutex error_mutex_;
  std::string error_;
  RTCDevice device_ = nullptr;
  RTCScene scene_ = nullptr;
  double build_seconds_ = 0.0;
  uint32_t instance_base_ = 0;
  std::vector<RTCScene> prototypes_;  // per prototype: its scene, or null when nothing places it
  std::unique_ptr<InstanceGeometryData> compact_;
  bool compact_bvh_ = false;
  RTCSceneFlags scene_flags() const {
    return compact_bvh_ ? RTC_SCENE_FLAG_ROBUST | RTC_SCENE_FLAG_COMPACT : RTC_SCENE_FLAG_ROBUST;
  }
  const TexturePools* textures_ = nullptr;
  std::vector<std::unique_ptr<AlphaFilterData>> alpha_data_;
  std::vector<std::unique_ptr<QuadricGeometryData>> quadric_data_;
  std::vector<std::unique_ptr<BilinearGeometryData>> bilinear_data_;
  std::atomic<int64_t> bytes_{0}, peak_bytes_{0};
};

}  // namespace lantern
