#include "accel/embree_scene.h"

#include <tbb/parallel_for.h>

#include <chrono>
#include <stdexcept>
#include <string>
#include <mutex>

namespace lantern {

// Embree traces a flat curve as a chain of ray-facing quads. A ray leaving
// a fibre starts within two widths of it, where a coarse chain of chords
// stands in its way: at Embree's default of 4 quads per segment (and at 8)
// the shadow rays of an environment-lit hair ball met their own fibres and
// darkened it by 7% against pbrt-v4; from 32 on the image no longer
// changes, nor does the render time measurably (docs/shapes.md).
static constexpr float kFlatCurveTessellation = 32.f;

// pbrt's flat and cylinder curves are ribbons facing the ray, ribbons are
// oriented by their normals (geometry/curve.h). The control points and
// normals are shared with the pool.
static RTCGeometry new_curve_geometry(RTCDevice device, const CurveSet& c) {
  const bool ribbon = c.type == CurveType::Ribbon;
  RTCGeometry geom = rtcNewGeometry(
      device, ribbon ? RTC_GEOMETRY_TYPE_NORMAL_ORIENTED_BEZIER_CURVE : RTC_GEOMETRY_TYPE_FLAT_BEZIER_CURVE);
  rtcSetSharedGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT4, c.control.data(), 0,
                             sizeof(glm::vec4), c.control.size());
  // Segment i starts at control point 4 i: Embree copies that index list.
  auto* first = static_cast<uint32_t*>(
      rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT, sizeof(uint32_t), c.segments()));
  for (uint32_t i = 0; i < c.segments(); ++i) first[i] = 4 * i;
  // The normals carry one padding element: Embree reads 16 bytes per entry.
  if (ribbon)
    rtcSetSharedGeometryBuffer(geom, RTC_BUFFER_TYPE_NORMAL, 0, RTC_FORMAT_FLOAT3, c.normals.data(), 0, sizeof(Vec3),
                               c.normals.size() - 1);
  else  // see kFlatCurveTessellation
    rtcSetGeometryTessellationRate(geom, kFlatCurveTessellation);
  return geom;
}

// What the top-level BVH holds: primitives stored once, and instances.
static size_t primitive_count(const ShapePools& shapes) {
  size_t n = shapes.instances.size() + shapes.spheres.size() + shapes.quadrics.size();
  for (const TriangleMesh& m : shapes.meshes) n += m.triangles.size() + m.quads.size();
  for (const BilinearPatchSet& p : shapes.patches) n += p.patches.size();
  for (const CurveSet& c : shapes.curves) n += c.segments();
  return n;
}

// Embree may report from its build threads, so the first message is kept
// under a lock and turned into an exception on the constructing thread.
void EmbreeScene::on_error(void* user, RTCError code, const char* str) {
  auto* self = static_cast<EmbreeScene*>(user);
  std::lock_guard<std::mutex> lock(self->error_mutex_);
  if (self->error_.empty()) self->error_ = "Embree error " + std::to_string(int(code)) + ": " + (str ? str : "");
}

void EmbreeScene::check(const char* what) {
  RTCError code = rtcGetDeviceError(device_);
  std::lock_guard<std::mutex> lock(error_mutex_);
  if (code != RTC_ERROR_NONE || !error_.empty())
    throw std::runtime_error(std::string("while ") + what + ": " + (error_.empty() ? "unknown Embree error" : error_));
}

bool EmbreeScene::on_memory(void* user, ssize_t bytes, bool) {
  auto* self = static_cast<EmbreeScene*>(user);
  int64_t now = self->bytes_.fetch_add(int64_t(bytes)) + int64_t(bytes);
  int64_t peak = self->peak_bytes_.load();
  while (now > peak && !self->peak_bytes_.compare_exchange_weak(peak, now)) {
  }
  return true;  // never refuse an allocation
}

// Attaches geometry `id` of the pools to `scene` as Embree geometry
// `embree_id`; the scene keeps the only reference.
void EmbreeScene::attach(RTCScene scene, const ShapePools& shapes, uint32_t id, uint32_t embree_id) {
  const Geometry& g = shapes.geometries[id];
  if (g.kind == ShapeKind::Mesh && shapes.meshes[g.index].triangle_count() == 0) return;  // an empty PLY: nothing to trace
  AlphaFilterData* alpha = nullptr;
  if (g.alpha >= 0) {
    alpha_data_.push_back(std::make_unique<AlphaFilterData>(AlphaFilterData{&shapes, textures_, id}));
    alpha = alpha_data_.back().get();
  }
  RTCGeometry geom;
  if (g.kind == ShapeKind::Quadric) {
    quadric_data_.push_back(std::make_unique<QuadricGeometryData>(QuadricGeometryData{&shapes.quadrics[g.index], alpha}));
    geom = new_quadric_geometry(device_, quadric_data_.back().get());
  } else if (g.kind == ShapeKind::Bilinear) {
    bilinear_data_.push_back(std::make_unique<BilinearGeometryData>(BilinearGeometryData{&shapes.patches[g.index], alpha}));
    geom = new_bilinear_geometry(device_, bilinear_data_.back().get());
  } else if (g.kind == ShapeKind::Curve) {
    geom = new_curve_geometry(device_, shapes.curves[g.index]);
  } else if (g.kind == ShapeKind::Mesh) {
    const TriangleMesh& m = shapes.meshes[g.index];
    const bool quads = !m.quads.empty();
    geom = rtcNewGeometry(device_, quads ? RTC_GEOMETRY_TYPE_QUAD : RTC_GEOMETRY_TYPE_TRIANGLE);
    // Shared buffers: Embree reads the pool's own arrays, no second copy.
    rtcSetSharedGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, m.positions.data(), 0,
                               sizeof(Vec3), m.vertex_count);
    if (quads)
      rtcSetSharedGeometryBuffer(geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT4, m.quads.data(), 0,
                                 sizeof(glm::uvec4), m.quads.size());
    else
      rtcSetSharedGeometryBuffer(geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, m.triangles.data(), 0,
                                 sizeof(glm::uvec3), m.triangles.size());
  } else {
    const Sphere& s = shapes.spheres[g.index];
    geom = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_SPHERE_POINT);
    auto* v = static_cast<float*>(
        rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT4, 4 * sizeof(float), 1));
    v[0] = s.center.x, v[1] = s.center.y, v[2] = s.center.z, v[3] = s.radius;
  }
  if (alpha && g.kind != ShapeKind::Quadric && g.kind != ShapeKind::Bilinear) {  // user geometry runs its filter itself
    rtcSetGeometryUserData(geom, alpha);
    rtcSetGeometryIntersectFilterFunction(geom, alpha_filter);
    rtcSetGeometryOccludedFilterFunction(geom, alpha_filter);
  }
  rtcCommitGeometry(geom);
  rtcAttachGeometryByID(scene, geom, embree_id);
  rtcReleaseGeometry(geom);
}

EmbreeScene::EmbreeScene(const ShapePools& shapes, const TexturePools& textures, MemoryLayout layout)
    : textures_(&textures) {
  device_ = rtcNewDevice(nullptr);
  if (!device_) throw std::runtime_error("cannot create the Embree device");
  rtcSetDeviceErrorFunction(device_, on_error, this);
  rtcSetDeviceMemoryMonitorFunction(device_, on_memory, this);
  scene_ = rtcNewScene(device_);
  // Watertight intersection: without it a ray can slip between two
  // triangles through their shared edge, and light leaks through closed
  // walls (tests/extremes_test.cpp, ScaleInvariance, caught it).
  //
  // Embree's compact BVH (indexed triangles, no copies of the vertices)
  // holds a quarter to a third less memory and, measured, traces a scene
  // of 13M primitives as fast but those of 1M and fewer 8-16% slower
  // (docs/performance.md, "Production scale").
  compact_bvh_ = layout == MemoryLayout::Compact ||
                 (layout == MemoryLayout::Auto && primitive_count(shapes) >= kCompactBvhFrom);
  rtcSetSceneFlags(scene_, scene_flags());
  rtcSetSceneBuildQuality(scene_, RTC_BUILD_QUALITY_HIGH);

  auto t0 = std::chrono::steady_clock::now();
  // Geometries traced directly keep their index as Embree geomID; those of
  // a prototype go into the prototype's own scene, numbered from 0. An
  // instance is instID base + k, and RayStream rewrites its hits back to
  // (geometry index, instance k).
  const uint32_t n = uint32_t(shapes.geometries.size());
  for (uint32_t id = 0; id < n; ++id) {
    if (id < shapes.in_prototype.size() && shapes.in_prototype[id]) continue;
    attach(scene_, shapes, id, id);
    check("adding geometry to the Embree scene");
  }
  instance_base_ = n;
  build_prototypes(shapes);
  place_instances(shapes, layout);
  rtcCommitScene(scene_);
  build_seconds_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  check("building the Embree BVH");
}

// Every prototype an instance uses becomes a scene of its own; their BVHs
// are built side by side (each build is parallel inside Embree too, but a
// small object's build is not).
void EmbreeScene::build_prototypes(const ShapePools& shapes) {
  prototypes_.assign(shapes.prototypes.size(), nullptr);
  std::vector<uint32_t> used;
  for (const Placement& inst : shapes.instances) {
    RTCScene& ps = prototypes_[inst.prototype];
    if (ps) continue;
    ps = rtcNewScene(device_);
    rtcSetSceneFlags(ps, scene_flags());
    rtcSetSceneBuildQuality(ps, RTC_BUILD_QUALITY_HIGH);
    const Prototype& proto = shapes.prototypes[inst.prototype];
    for (uint32_t j = 0; j < proto.count; ++j) attach(ps, shapes, proto.first + j, j);
    used.push_back(inst.prototype);
  }
  tbb::parallel_for(size_t(0), used.size(), [&](size_t i) { rtcCommitScene(prototypes_[used[i]]); });
  check("building the objects' BVHs");
}

// Moving instances are always Embree's (it interpolates their matrices);
// still ones are Embree's or, compact, primitives of one user geometry.
void EmbreeScene::place_instances(const ShapePools& shapes, MemoryLayout layout) {
  size_t still = 0;
  for (const Placement& inst : shapes.instances) still += inst.motion == Placement::kStill;
  const bool compact = layout == MemoryLayout::Compact || (layout == MemoryLayout::Auto && still >= kCompactInstancesFrom);
  if (compact && still > 0) {
    compact_ = std::make_unique<InstanceGeometryData>();
    compact_->placements = &shapes.instances;
    compact_->scenes = &prototypes_;
    compact_->instance_base = instance_base_;
    compact_->prototype_bounds.resize(prototypes_.size());
    for (size_t p = 0; p < prototypes_.size(); ++p)
      if (prototypes_[p]) rtcGetSceneBounds(prototypes_[p], &compact_->prototype_bounds[p]);
    if (still < shapes.instances.size())  // otherwise primitive k is placement k
      for (uint32_t k = 0; k < shapes.instances.size(); ++k)
        if (shapes.instances[k].motion == Placement::kStill) compact_->placement_of.push_back(k);
    RTCGeometry g = new_instance_geometry(device_, compact_.get(), uint32_t(still));
    rtcCommitGeometry(g);
    // Its own geomID is never reported (hits carry the prototype's geometry
    // and instID base + k); it takes the first still instance's, which no
    // Embree instance holds, so Embree's tables indexed by geomID do not
    // grow by an entry per placement.
    const uint32_t first_still = compact_->placement_of.empty() ? 0 : compact_->placement_of.front();
    rtcAttachGeometryByID(scene_, g, instance_base_ + first_still);
    rtcReleaseGeometry(g);
    check("adding the instances to the Embree scene");
  }
  for (uint32_t k = 0; k < shapes.instances.size(); ++k) {
    const Placement& inst = shapes.instances[k];
    if (compact && inst.motion == Placement::kStill) continue;
    RTCGeometry g = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_INSTANCE);
    rtcSetGeometryInstancedScene(g, prototypes_[inst.prototype]);
    if (inst.motion == Placement::kStill) {
      rtcSetGeometryTransform(g, 0, RTC_FORMAT_FLOAT3X4_COLUMN_MAJOR, &inst.world_from_object[0][0]);
    } else {
      // Embree interpolates the matrices linearly between equally spaced
      // steps, as MotionPath::at does for shading (math/motion.h).
      const std::vector<Mat4>& steps = shapes.motions[inst.motion].steps;
      rtcSetGeometryTimeStepCount(g, unsigned(steps.size()));
      for (size_t t = 0; t < steps.size(); ++t)
        rtcSetGeometryTransform(g, unsigned(t), RTC_FORMAT_FLOAT4X4_COLUMN_MAJOR, &steps[t][0][0]);
    }
    rtcCommitGeometry(g);
    rtcAttachGeometryByID(scene_, g, instance_base_ + k);
    rtcReleaseGeometry(g);
    check("adding an instance to the Embree scene");
  }
}

EmbreeScene::~EmbreeScene() {
  if (scene_) rtcReleaseScene(scene_);
  for (RTCScene ps : prototypes_)
    if (ps) rtcReleaseScene(ps);
  if (device_) rtcReleaseDevice(device_);
}

void EmbreeScene::bounds(Vec3* lo, Vec3* hi) const {
  RTCBounds b;
  rtcGetSceneBounds(scene_, &b);
  *lo = Vec3(b.lower_x, b.lower_y, b.lower_z);
  *hi = Vec3(b.upper_x, b.upper_y, b.upper_z);
}

}  // namespace lantern
