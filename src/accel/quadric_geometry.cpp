#include "accel/quadric_geometry.h"

#include <type_traits>

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
  Vec3 n = q.normal_to_world * quadric_object_normal(q, quadric_object_point(q, h.uv));
  if (q.flip_normal) n = -n;
  hit.Ng_x = n.x, hit.Ng_y = n.y, hit.Ng_z = n.z;
  hit.u = h.uv.x, hit.v = h.uv.y;
  hit.primID = 0;
  hit.geomID = geom_id;
  hit.instID[0] = ctx->instID[0];
  return hit;
}

// Whether the alpha filter keeps a candidate: ray i with tfar at the hit.
template <typename Args>
bool keeps(const Args* args, const QuadricGeometryData* d, const RayView& rv, float t, RTCHit hit) {
  if (!d->alpha) return true;
  RTCRay ray{};
  ray.org_x = float(rv.o.x), ray.org_y = float(rv.o.y), ray.org_z = float(rv.o.z);
  ray.dir_x = float(rv.d.x), ray.dir_y = float(rv.d.y), ray.dir_z = float(rv.d.z);
  ray.tnear = rv.tnear;
  ray.tfar = t;
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
template <typename Accept>
bool first_hit(const QuadricGeometryData* d, const RayView& rv, QuadricHit* h, const Accept& accept) {
  double t_min = rv.tnear;
  while (intersect_quadric(*d->quadric, rv.o, rv.d, t_min, rv.tfar, h)) {
    if (float(h->t) <= rv.tnear) return false;
    if (accept(*h)) return true;
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
    const RayView rv = ray_of(ray, n, i);
    QuadricHit h;
    RTCHit hit;
    auto accept = [&](const QuadricHit& c) {
      hit = hit_of(*d->quadric, c, args->geomID, args->context);
      return float(c.t) < rv.tfar && keeps(args, d, rv, float(c.t), hit);
    };
    if (!first_hit(d, rv, &h, accept)) continue;
    RTCRayN_tfar(ray, n, i) = float(h.t);
    RTCHitN_Ng_x(hits, n, i) = hit.Ng_x;
    RTCHitN_Ng_y(hits, n, i) = hit.Ng_y;
    RTCHitN_Ng_z(hits, n, i) = hit.Ng_z;
    RTCHitN_u(hits, n, i) = hit.u;
    RTCHitN_v(hits, n, i) = hit.v;
    RTCHitN_primID(hits, n, i) = 0;
    RTCHitN_geomID(hits, n, i) = args->geomID;
    RTCHitN_instID(hits, n, i, 0) = args->context->instID[0];
  }
}

void occluded(const RTCOccludedFunctionNArguments* args) {
  const auto* d = static_cast<const QuadricGeometryData*>(args->geometryUserPtr);
  const unsigned n = args->N;
  for (unsigned i = 0; i < n; ++i) {
    if (args->valid[i] != -1) continue;
    const RayView rv = ray_of(args->ray, n, i);
    QuadricHit h;
    auto accept = [&](const QuadricHit& c) {
      return float(c.t) < rv.tfar &&
             keeps(args, d, rv, float(c.t), hit_of(*d->quadric, c, args->geomID, args->context));
    };
    if (first_hit(d, rv, &h, accept)) RTCRayN_tfar(args->ray, n, i) = -kInfinity;
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
