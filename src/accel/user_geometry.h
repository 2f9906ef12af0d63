// What every shape Embree traces through user geometry shares (quadrics,
// bilinear patches): reading a ray of a stream, and the intersect and
// occluded callbacks around a shape's own exact test. The shape supplies
//   bool first_crossing(uint32_t prim, const RayView& r, double t_min, UserHit* h)
// (the nearest crossing beyond t_min, in (r.tnear, r.tfar) or not) and
//   Vec3 normal(uint32_t prim, Vec2 uv)  (reported to Embree as Ng).
// Embree calls no filter function on user geometry by itself, so an
// alpha-cut shape runs the alpha filter through rtcFilterIntersection /
// rtcFilterOcclusion on each candidate, and a rejected candidate moves the
// search past it.
#pragma once

#include <embree3/rtcore.h>

#include <glm/vec3.hpp>
#include <type_traits>

#include "accel/alpha_filter.h"

namespace lantern::user_geometry {

struct RayView {
  glm::dvec3 o, d;
  float tnear, tfar;
};

struct UserHit {
  double t;
  Vec2 uv;
};

inline RayView ray_of(RTCRayN* ray, unsigned n, unsigned i) {
  return {glm::dvec3(RTCRayN_org_x(ray, n, i), RTCRayN_org_y(ray, n, i), RTCRayN_org_z(ray, n, i)),
          glm::dvec3(RTCRayN_dir_x(ray, n, i), RTCRayN_dir_y(ray, n, i), RTCRayN_dir_z(ray, n, i)),
          RTCRayN_tnear(ray, n, i), RTCRayN_tfar(ray, n, i)};
}

template <class Shape>
RTCHit hit_of(const Shape& s, uint32_t prim, const UserHit& h, unsigned geom_id, const RTCIntersectContext* ctx) {
  RTCHit hit{};
  const Vec3 n = s.normal(prim, h.uv);
  hit.Ng_x = n.x, hit.Ng_y = n.y, hit.Ng_z = n.z;
  hit.u = h.uv.x, hit.v = h.uv.y;
  hit.primID = prim;
  hit.geomID = geom_id;
  hit.instID[0] = ctx->instID[0];
  return hit;
}

// Whether the alpha filter keeps candidate c: always without alpha, so an
// opaque shape builds no hit record for its candidates.
template <class Shape, class Args>
bool keeps(const Args* args, const Shape& s, AlphaFilterData* alpha, uint32_t prim, const RayView& rv,
           const UserHit& c) {
  if (!alpha) return true;
  RTCHit hit = hit_of(s, prim, c, args->geomID, args->context);
  RTCRay ray{};
  ray.org_x = float(rv.o.x), ray.org_y = float(rv.o.y), ray.org_z = float(rv.o.z);
  ray.dir_x = float(rv.d.x), ray.dir_y = float(rv.d.y), ray.dir_z = float(rv.d.z);
  ray.tnear = rv.tnear;
  ray.tfar = float(c.t);
  ray.mask = 0xFFFFFFFFu;
  int valid = -1;
  RTCFilterFunctionNArguments fa;
  fa.valid = &valid;
  fa.geometryUserPtr = alpha;
  fa.context = args->context;
  fa.ray = reinterpret_cast<RTCRayN*>(&ray);
  fa.hit = reinterpret_cast<RTCHitN*>(&hit);
  fa.N = 1;
  if constexpr (std::is_same_v<Args, RTCOccludedFunctionNArguments>)
    rtcFilterOcclusion(args, &fa);
  else
    rtcFilterIntersection(args, &fa);
  return valid == -1;
}

// The first kept crossing of primitive prim by ray rv, if any.
template <class Shape, class Args>
bool first_hit(const Args* args, const Shape& s, AlphaFilterData* alpha, uint32_t prim, const RayView& rv, UserHit* h) {
  double t_min = rv.tnear;
  while (s.first_crossing(prim, rv, t_min, h)) {
    const float t = float(h->t);
    if (t <= rv.tnear || !(t < rv.tfar)) return false;  // rounded onto the ray's ends
    if (keeps(args, s, alpha, prim, rv, *h)) return true;
    t_min = h->t;
  }
  return false;
}

template <class Shape>
void intersect(const RTCIntersectFunctionNArguments* args, const Shape& s, AlphaFilterData* alpha) {
  const unsigned n = args->N;
  RTCRayN* ray = RTCRayHitN_RayN(args->rayhit, n);
  RTCHitN* hits = RTCRayHitN_HitN(args->rayhit, n);
  for (unsigned i = 0; i < n; ++i) {
    if (args->valid[i] != -1) continue;
    UserHit h;
    if (!first_hit(args, s, alpha, args->primID, ray_of(ray, n, i), &h)) continue;
    const RTCHit hit = hit_of(s, args->primID, h, args->geomID, args->context);
    RTCRayN_tfar(ray, n, i) = float(h.t);
    RTCHitN_Ng_x(hits, n, i) = hit.Ng_x;
    RTCHitN_Ng_y(hits, n, i) = hit.Ng_y;
    RTCHitN_Ng_z(hits, n, i) = hit.Ng_z;
    RTCHitN_u(hits, n, i) = hit.u;
    RTCHitN_v(hits, n, i) = hit.v;
    RTCHitN_primID(hits, n, i) = hit.primID;
    RTCHitN_geomID(hits, n, i) = hit.geomID;
    RTCHitN_instID(hits, n, i, 0) = hit.instID[0];
  }
}

template <class Shape>
void occluded(const RTCOccludedFunctionNArguments* args, const Shape& s, AlphaFilterData* alpha) {
  const unsigned n = args->N;
  for (unsigned i = 0; i < n; ++i) {
    if (args->valid[i] != -1) continue;
    UserHit h;
    if (first_hit(args, s, alpha, args->primID, ray_of(args->ray, n, i), &h))
      RTCRayN_tfar(args->ray, n, i) = -kInfinity;
  }
}

// A user geometry of `count` primitives with these callbacks. With alpha,
// the alpha filter is registered so that keeps() can run it through
// rtcFilterIntersection / rtcFilterOcclusion. To be committed by the caller.
inline RTCGeometry create(RTCDevice device, unsigned count, void* user_data, bool alpha, RTCBoundsFunction bounds,
                          RTCIntersectFunctionN intersect, RTCOccludedFunctionN occluded) {
  RTCGeometry g = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_USER);
  rtcSetGeometryUserPrimitiveCount(g, count);
  rtcSetGeometryUserData(g, user_data);
  rtcSetGeometryBoundsFunction(g, bounds, nullptr);
  rtcSetGeometryIntersectFunction(g, intersect);
  rtcSetGeometryOccludedFunction(g, occluded);
  if (alpha) {
    rtcSetGeometryIntersectFilterFunction(g, alpha_filter);
    rtcSetGeometryOccludedFilterFunction(g, alpha_filter);
  }
  return g;
}

}  // namespace lantern::user_geometry
