#include "accel/quadric_geometry.h"

#include <type_traits>

#include "scene/surface.h"

namespace lantern {

namespace {

void bounds(const RTCBoundsFunctionArguments* args) {
  const auto* d = static_cast<const QuadricGeometryData*>(args->geometryUserPtr);
  Vec3 lo, hi;
  quadric_bounds(*d->quadric, &lo, &hi);
  RTCBounds* b = args->bounds_o;
  b->lower_x = lo.x, b->lower_y = lo.y, b->lower_z = lo.z;
  b->upper_x = hi.x, b->upper_y = hi.y, b->upper_z = hi.z;
}

struct RayView {
  glm::dvec3 o, d;
  float tnear, tfar;
};

RayView ray_of(RTCRayN* ray, unsigned n, unsigned i) {
  return {glm::dvec3(RTCRayN_org_x(ray, n, i), RTCRayN_org_y(ray, n, i), RTCRayN_org_z(ray, n, i)),
          glm::dvec3(RTCRayN_dir_x(ray, n, i), RTCRayN_dir_y(ray, n, i), RTCRayN_dir_z(ray, n, i)),
          RTCRayN_tnear(ray, n, i), RTCRayN_tfar(ray, n, i)};
}

RTCHit hit_of(const Quadric& q, const QuadricHit& h, unsigned geom_id, const RTCIntersectContext* ctx) {
  RTCHit hit{};
  const Vec3 n = quadric_point(q, h.uv).ng;
  hit.Ng_x = n.x, hit.Ng_y = n.y, hit.Ng_z = n.z;
  hit.u = h.uv.x, hit.v = h.uv.y;
  hit.primID = 0;
  hit.geomID = geom_id;
  hit.instID[0] = ctx->instID[0];
  return hit;
}

// Whether the alpha filter keeps candidate c of ray rv: always without
// alpha, so an opaque quadric builds no hit record for its candidates.
template <typename Args>
bool keeps(const Args* args, const QuadricGeometryData* d, const RayView& rv, const QuadricHit& c) {
  if (!d->alpha) return true;
  RTCHit hit = hit_of(*d->quadric, c, args->geomID, args->context);
  RTCRay ray{};
  ray.org_x = float(rv.o.x), ray.org_y = float(rv.o.y), ray.org_z = float(rv.o.z);
  ray.dir_x = float(rv.d.x), ray.dir_y = float(rv.d.y), ray.dir_z = float(rv.d.z);
  ray.tnear = rv.tnear;
  ray.tfar = float(c.t);
  ray.mask = 0xFFFFFFFFu;
  int valid = -1;
  RTCFilterFunctionNArguments fa;
  fa.valid = &valid;
  fa.geometryUserPtr = d->alpha;
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

// The first kept hit of ray rv, if any. A rejected candidate moves the
// search past it; a quadric has at most two.
template <typename Args>
bool first_hit(const Args* args, const QuadricGeometryData* d, const RayView& rv, QuadricHit* h) {
  double t_min = rv.tnear;
  while (intersect_quadric(*d->quadric, rv.o, rv.d, t_min, rv.tfar, h)) {
    const float t = float(h->t);
    if (t <= rv.tnear || !(t < rv.tfar)) return false;  // rounded onto the ray's ends
    if (keeps(args, d, rv, *h)) return true;
    t_min = h->t;
  }
  return false;
}

void intersect(const RTCIntersectFunctionNArguments* args) {
  const auto* d = static_cast<const QuadricGeometryData*>(args->geometryUserPtr);
  const unsigned n = args->N;
  RTCRayN* ray = RTCRayHitN_RayN(args->rayhit, n);
  RTCHitN* hits = RTCRayHitN_HitN(args->rayhit, n);
  for (unsigned i = 0; i < n; ++i) {
    if (args->valid[i] != -1) continue;
    QuadricHit h;
    if (!first_hit(args, d, ray_of(ray, n, i), &h)) continue;
    const RTCHit hit = hit_of(*d->quadric, h, args->geomID, args->context);
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

void occluded(const RTCOccludedFunctionNArguments* args) {
  const auto* d = static_cast<const QuadricGeometryData*>(args->geometryUserPtr);
  const unsigned n = args->N;
  for (unsigned i = 0; i < n; ++i) {
    if (args->valid[i] != -1) continue;
    QuadricHit h;
    if (first_hit(args, d, ray_of(args->ray, n, i), &h)) RTCRayN_tfar(args->ray, n, i) = -kInfinity;
  }
}

}  // namespace

RTCGeometry new_quadric_geometry(RTCDevice device, QuadricGeometryData* data) {
  RTCGeometry g = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_USER);
  rtcSetGeometryUserPrimitiveCount(g, 1);
  rtcSetGeometryUserData(g, data);
  rtcSetGeometryBoundsFunction(g, bounds, nullptr);
  rtcSetGeometryIntersectFunction(g, intersect);
  rtcSetGeometryOccludedFunction(g, occluded);
  if (data->alpha) {
    rtcSetGeometryIntersectFilterFunction(g, alpha_filter);
    rtcSetGeometryOccludedFilterFunction(g, alpha_filter);
  }
  return g;
}

}  // namespace lantern
