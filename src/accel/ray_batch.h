// A batch of rays and their hits in structure-of-arrays form: exactly the
// layout Embree's RTCRayHitNp points into, so the stream back end passes the
// arrays straight through.
#pragma once

#include <algorithm>
#include <cstdint>
#include <vector>

#include "math/common.h"

namespace lantern {

template <class T>
size_t vector_bytes(const std::vector<T>& v) {
  return v.capacity() * sizeof(T);
}

inline constexpr uint32_t kInvalidGeometry = 0xFFFFFFFFu;  // RTC_INVALID_GEOMETRY_ID

struct RayBatch {
  std::vector<float> org_x, org_y, org_z, tnear, dir_x, dir_y, dir_z, time, tfar;
  std::vector<uint32_t> mask, id, flags;
  std::vector<float> ng_x, ng_y, ng_z, u, v;
  std::vector<uint32_t> prim_id, geom_id, inst_id;
  uint32_t count = 0;

  void reserve(size_t n) {
    for (auto* a : {&org_x, &org_y, &org_z, &tnear, &dir_x, &dir_y, &dir_z, &time, &tfar, &ng_x, &ng_y, &ng_z, &u, &v})
      a->resize(n);
    for (auto* a : {&mask, &id, &flags, &prim_id, &geom_id, &inst_id}) a->resize(n);
  }
  size_t capacity() const { return org_x.size(); }
  size_t memory_bytes() const { return capacity() * (14 * sizeof(float) + 6 * sizeof(uint32_t)); }

  // Appends a ray, growing the arrays when full; d need not be unit length
  // (t is then in units of |d|). time: where in the shutter interval the
  // ray's path is, in [0, 1] (math/motion.h); moving geometry is traced
  // where it is then, all else ignores it.
  uint32_t push(const Vec3& o, const Vec3& d, float t_min, float t_max, float ray_time) {
    if (count == org_x.size()) reserve(std::max<size_t>(64, 2 * org_x.size()));
    uint32_t i = count++;
    org_x[i] = o.x, org_y[i] = o.y, org_z[i] = o.z;
    dir_x[i] = d.x, dir_y[i] = d.y, dir_z[i] = d.z;
    tnear[i] = t_min;
    tfar[i] = t_max;
    time[i] = ray_time;
    mask[i] = 0xFFFFFFFFu;
    id[i] = i;
    flags[i] = 0;
    geom_id[i] = kInvalidGeometry;
    inst_id[i] = kInvalidGeometry;
    return i;
  }
  // Appends a copy of ray i with its hit.
  uint32_t push_copy(uint32_t i) {
    const uint32_t j = push(origin(i), direction(i), tnear[i], tfar[i], time[i]);
    mask[j] = mask[i], flags[j] = flags[i];
    ng_x[j] = ng_x[i], ng_y[j] = ng_y[i], ng_z[j] = ng_z[i], u[j] = u[i], v[j] = v[i];
    prim_id[j] = prim_id[i], geom_id[j] = geom_id[i], inst_id[j] = inst_id[i];
    return j;
  }
  Vec3 origin(uint32_t i) const { return Vec3(org_x[i], org_y[i], org_z[i]); }
  Vec3 direction(uint32_t i) const { return Vec3(dir_x[i], dir_y[i], dir_z[i]); }
  bool hit(uint32_t i) const { return geom_id[i] != kInvalidGeometry; }
  // After an occlusion query Embree sets tfar to -inf for blocked rays.
  bool occluded(uint32_t i) const { return tfar[i] < 0.f; }
};

}  // namespace lantern
