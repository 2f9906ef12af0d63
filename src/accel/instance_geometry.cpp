#include "accel/instance_geometry.h"

#include <glm/mat3x3.hpp>

#include "accel/user_geometry.h"

namespace lantern {

namespace {

// The ray of lane i carried into placement k's prototype space. The
// direction is not normalised, so distances along it stay the world's.
RTCRay object_ray(RTCRayN* ray, unsigned n, unsigned i, const glm::mat4x3& M) {
  const glm::mat3 inv = glm::inverse(glm::mat3(M));
  const Vec3 o = inv * (Vec3(RTCRayN_org_x(ray, n, i), RTCRayN_org_y(ray, n, i), RTCRayN_org_z(ray, n, i)) - M[3]);
  const Vec3 d = inv * Vec3(RTCRayN_dir_x(ray, n, i), RTCRayN_dir_y(ray, n, i), RTCRayN_dir_z(ray, n, i));
  RTCRay r;
  r.org_x = o.x, r.org_y = o.y, r.org_z = o.z, r.tnear = RTCRayN_tnear(ray, n, i);
  r.dir_x = d.x, r.dir_y = d.y, r.dir_z = d.z, r.time = RTCRayN_time(ray, n, i);
  r.tfar = RTCRayN_tfar(ray, n, i), r.mask = RTCRayN_mask(ray, n, i), r.id = RTCRayN_id(ray, n, i), r.flags = 0;
  return r;
}

void instance_bounds_fn(const RTCBoundsFunctionArguments* args) {
  const auto* d = static_cast<const InstanceGeometryData*>(args->geometryUserPtr);
  const Placement& p = (*d->placements)[d->placement(args->primID)];
  const RTCBounds& b = d->prototype_bounds[p.prototype];
  RTCBounds* o = args->bounds_o;
  if (!(b.lower_x <= b.upper_x)) {  // nothing to trace (an empty PLY): an empty box, which Embree leaves out
    o->lower_x = o->lower_y = o->lower_z = INFINITY;
    o->upper_x = o->upper_y = o->upper_z = -INFINITY;
    return;
  }
  Vec3 lo(INFINITY), hi(-INFINITY);
  for (int c = 0; c < 8; ++c) {
    const Vec3 corner(c & 1 ? b.upper_x : b.lower_x, c & 2 ? b.upper_y : b.lower_y, c & 4 ? b.upper_z : b.lower_z);
    const Vec3 w = p.world_from_object * Vec4(corner, 1.f);
    lo = glm::min(lo, w), hi = glm::max(hi, w);
  }
  // A corner's rounding must not cut the box: widen by a few ulps.
  const Vec3 pad = 4.f * 1.2e-7f * glm::max(glm::abs(lo), glm::abs(hi));
  lo -= pad, hi += pad;
  o->lower_x = lo.x, o->lower_y = lo.y, o->lower_z = lo.z;
  o->upper_x = hi.x, o->upper_y = hi.y, o->upper_z = hi.z;
}

// Each lane is traced on its own: the prototype's scene is an Embree scene
// like any other, and rtcIntersect1 from a user geometry's callback is how
// Embree's documentation builds instancing out of user geometry.
void instance_intersect_fn(const RTCIntersectFunctionNArguments* args) {
  const auto* d = static_cast<const InstanceGeometryData*>(args->geometryUserPtr);
  const uint32_t k = d->placement(args->primID);
  const Placement& p = (*d->placements)[k];
  RTCRayN* ray = RTCRayHitN_RayN(args->rayhit, args->N);
  RTCHitN* hit = RTCRayHitN_HitN(args->rayhit, args->N);
  RTCIntersectContext* ctx = args->context;
  for (unsigned i = 0; i < args->N; ++i) {
    if (args->valid[i] != -1) continue;
    RTCRayHit rh;
    rh.ray = object_ray(ray, args->N, i, p.world_from_object);
    rh.hit.geomID = rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
    ctx->instID[0] = d->instance_base + k;
    rtcIntersect1((*d->scenes)[p.prototype], ctx, &rh);
    ctx->instID[0] = RTC_INVALID_GEOMETRY_ID;
    if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) continue;
    RTCRayN_tfar(ray, args->N, i) = rh.ray.tfar;
    RTCHitN_Ng_x(hit, args->N, i) = rh.hit.Ng_x;
    RTCHitN_Ng_y(hit, args->N, i) = rh.hit.Ng_y;
    RTCHitN_Ng_z(hit, args->N, i) = rh.hit.Ng_z;
    RTCHitN_u(hit, args->N, i) = rh.hit.u;
    RTCHitN_v(hit, args->N, i) = rh.hit.v;
    RTCHitN_primID(hit, args->N, i) = rh.hit.primID;
    RTCHitN_geomID(hit, args->N, i) = rh.hit.geomID;
    RTCHitN_instID(hit, args->N, i, 0) = d->instance_base + k;
  }
}

void instance_occluded_fn(const RTCOccludedFunctionNArguments* args) {
  const auto* d = static_cast<const InstanceGeometryData*>(args->geometryUserPtr);
  const uint32_t k = d->placement(args->primID);
  const Placement& p = (*d->placements)[k];
  RTCIntersectContext* ctx = args->context;
  for (unsigned i = 0; i < args->N; ++i) {
    if (args->valid[i] != -1) continue;
    RTCRay r = object_ray(args->ray, args->N, i, p.world_from_object);
    ctx->instID[0] = d->instance_base + k;
    rtcOccluded1((*d->scenes)[p.prototype], ctx, &r);
    ctx->instID[0] = RTC_INVALID_GEOMETRY_ID;
    if (r.tfar < 0.f) RTCRayN_tfar(args->ray, args->N, i) = -INFINITY;
  }
}

}  // namespace

// No alpha filter of its own: the prototypes' geometries run theirs.
RTCGeometry new_instance_geometry(RTCDevice device, InstanceGeometryData* data, uint32_t count) {
  return user_geometry::create(device, count, data, false, instance_bounds_fn, instance_intersect_fn,
                               instance_occluded_fn);
}

}  // namespace lantern
