#include "accel/bilinear_geometry.h"

#include "accel/user_geometry.h"

namespace lantern {

namespace {

using user_geometry::RayView;
using user_geometry::UserHit;

struct PatchShape {
  const BilinearPatchSet& s;
  bool first_crossing(uint32_t prim, const RayView& r, double t_min, UserHit* h) const {
    return intersect_bilinear_patch(patch_corners(s, prim), r.o, r.d, t_min, r.tfar, &h->t, &h->uv);
  }
  Vec3 normal(uint32_t prim, Vec2 uv) const { return bilinear_normal(s, prim, uv); }
};

void patch_bounds_fn(const RTCBoundsFunctionArguments* args) {
  const auto* d = static_cast<const BilinearGeometryData*>(args->geometryUserPtr);
  const PatchCorners c = patch_corners(*d->patches, args->primID);
  Vec3 lo = glm::min(glm::min(c.p00, c.p10), glm::min(c.p01, c.p11));
  Vec3 hi = glm::max(glm::max(c.p00, c.p10), glm::max(c.p01, c.p11));
  // The patch lies in its corners' hull; pad for rounding.
  const Vec3 pad = 1e-6f * glm::max(glm::abs(lo), glm::abs(hi)) + Vec3(1e-30f);
  lo -= pad;
  hi += pad;
  RTCBounds* b = args->bounds_o;
  b->lower_x = lo.x, b->lower_y = lo.y, b->lower_z = lo.z;
  b->upper_x = hi.x, b->upper_y = hi.y, b->upper_z = hi.z;
}

void patch_intersect_fn(const RTCIntersectFunctionNArguments* args) {
  const auto* d = static_cast<const BilinearGeometryData*>(args->geometryUserPtr);
  user_geometry::intersect(args, PatchShape{*d->patches}, d->alpha);
}

void patch_occluded_fn(const RTCOccludedFunctionNArguments* args) {
  const auto* d = static_cast<const BilinearGeometryData*>(args->geometryUserPtr);
  user_geometry::occluded(args, PatchShape{*d->patches}, d->alpha);
}

}  // namespace

RTCGeometry new_bilinear_geometry(RTCDevice device, BilinearGeometryData* data) {
  return user_geometry::create(device, unsigned(data->patches->patches.size()), data, data->alpha != nullptr,
                               patch_bounds_fn, patch_intersect_fn, patch_occluded_fn);
}

}  // namespace lantern
