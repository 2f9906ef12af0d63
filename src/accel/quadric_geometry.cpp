#include "accel/quadric_geometry.h"

#include "accel/user_geometry.h"
#include "geometry/surface.h"

namespace lantern {

namespace {

using user_geometry::RayView;
using user_geometry::UserHit;

// The quadric as user_geometry's callbacks see it: one primitive.
struct QuadricShape {
  const Quadric& q;
  bool first_crossing(uint32_t, const RayView& r, double t_min, UserHit* h) const {
    QuadricHit qh;
    if (!intersect_quadric(q, r.o, r.d, t_min, r.tfar, &qh)) return false;
    *h = {qh.t, qh.uv};
    return true;
  }
  Vec3 normal(uint32_t, Vec2 uv) const { return quadric_point(q, uv).ng; }
};

void quadric_bounds_fn(const RTCBoundsFunctionArguments* args) {
  const auto* d = static_cast<const QuadricGeometryData*>(args->geometryUserPtr);
  Vec3 lo, hi;
  quadric_bounds(*d->quadric, &lo, &hi);
  RTCBounds* b = args->bounds_o;
  b->lower_x = lo.x, b->lower_y = lo.y, b->lower_z = lo.z;
  b->upper_x = hi.x, b->upper_y = hi.y, b->upper_z = hi.z;
}

void quadric_intersect_fn(const RTCIntersectFunctionNArguments* args) {
  const auto* d = static_cast<const QuadricGeometryData*>(args->geometryUserPtr);
  user_geometry::intersect(args, QuadricShape{*d->quadric}, d->alpha);
}

void quadric_occluded_fn(const RTCOccludedFunctionNArguments* args) {
  const auto* d = static_cast<const QuadricGeometryData*>(args->geometryUserPtr);
  user_geometry::occluded(args, QuadricShape{*d->quadric}, d->alpha);
}

}  // namespace

RTCGeometry new_quadric_geometry(RTCDevice device, QuadricGeometryData* data) {
  return user_geometry::create(device, 1, data, data->alpha != nullptr, quadric_bounds_fn, quadric_intersect_fn,
                               quadric_occluded_fn);
}

}  // namespace lantern
