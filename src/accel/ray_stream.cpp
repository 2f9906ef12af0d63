#include "accel/ray_stream.h"

#include <chrono>

#include "accel/ray_dump.h"

#include <stdexcept>

namespace lantern {

RayStream::RayStream(RTCScene scene, RayBackend backend, RayCounters* counters)
    : scene_(scene), backend_(backend), counters_(counters) {}

static RTCRayHitNp soa_view(RayBatch& b) {
  RTCRayHitNp r;
  r.ray.org_x = b.org_x.data();
  r.ray.org_y = b.org_y.data();
  r.ray.org_z = b.org_z.data();
  r.ray.tnear = b.tnear.data();
  r.ray.dir_x = b.dir_x.data();
  r.ray.dir_y = b.dir_y.data();
  r.ray.dir_z = b.dir_z.data();
  r.ray.time = b.time.data();
  r.ray.tfar = b.tfar.data();
  r.ray.mask = b.mask.data();
  r.ray.id = b.id.data();
  r.ray.flags = b.flags.data();
  r.hit.Ng_x = b.ng_x.data();
  r.hit.Ng_y = b.ng_y.data();
  r.hit.Ng_z = b.ng_z.data();
  r.hit.u = b.u.data();
  r.hit.v = b.v.data();
  r.hit.primID = b.prim_id.data();
  r.hit.geomID = b.geom_id.data();
  r.hit.instID[0] = b.inst_id.data();
  return r;
}

static RTCRay aos_ray(const RayBatch& b, uint32_t i) {
  RTCRay r;
  r.org_x = b.org_x[i], r.org_y = b.org_y[i], r.org_z = b.org_z[i], r.tnear = b.tnear[i];
  r.dir_x = b.dir_x[i], r.dir_y = b.dir_y[i], r.dir_z = b.dir_z[i], r.time = b.time[i];
  r.tfar = b.tfar[i], r.mask = 0xFFFFFFFFu, r.id = i, r.flags = 0;
  return r;
}

static void store_hit(RayBatch& b, uint32_t i, const RTCRay& r, const RTCHit& h) {
  b.tfar[i] = r.tfar;
  b.ng_x[i] = h.Ng_x, b.ng_y[i] = h.Ng_y, b.ng_z[i] = h.Ng_z;
  b.u[i] = h.u, b.v[i] = h.v;
  b.prim_id[i] = h.primID, b.geom_id[i] = h.geomID, b.inst_id[i] = h.instID[0];
}

template <class Packet>
static void load_packet(Packet& p, const RayBatch& b, uint32_t base, int* valid) {
  for (uint32_t k = 0; k < 16; ++k) {
    uint32_t i = base + k;
    valid[k] = i < b.count ? -1 : 0;
    if (i >= b.count) i = base;  // keep lanes well defined
    p.org_x[k] = b.org_x[i], p.org_y[k] = b.org_y[i], p.org_z[k] = b.org_z[i], p.tnear[k] = b.tnear[i];
    p.dir_x[k] = b.dir_x[i], p.dir_y[k] = b.dir_y[i], p.dir_z[k] = b.dir_z[i], p.time[k] = b.time[i];
    p.tfar[k] = b.tfar[i], p.mask[k] = 0xFFFFFFFFu, p.id[k] = k, p.flags[k] = 0;
  }
}

void RayStream::intersect(RayBatch& b, RayKind kind) {
  if (b.count == 0) return;
  if (counters_) {
    switch (kind) {
      case RayKind::Camera: counters_->camera += b.count; break;
      case RayKind::LightExtension: counters_->light += b.count; break;
      case RayKind::Shadow: counters_->shadow += b.count; break;  // transmittance through media
      default: counters_->extension += b.count; break;
    }
  }
  if (dump_) dump_->write(kind, b);
  if (!timing_ && !trace_) {
    run_intersect(b, kind);
  } else {
    const auto t0 = TraceClock::now();
    run_intersect(b, kind);
    record(kind, b.count, t0, TraceClock::now());
  }
  if (has_instances_) remap_instance_hits(b);
  if (has_quads_) remap_quad_hits(b);
}

void RayStream::remap_quad_hits(RayBatch& b) const {
  for (uint32_t i = 0; i < b.count; ++i) {
    if (b.geom_id[i] == RTC_INVALID_GEOMETRY_ID) continue;
    const Geometry& g = shapes_->geometries[b.geom_id[i]];
    if (g.kind != ShapeKind::Mesh || shapes_->meshes[g.index].quads.empty()) continue;
    b.prim_id[i] = quad_hit_triangle(b.prim_id[i], b.u[i], b.v[i], &b.u[i], &b.v[i]);
  }
}

void RayStream::remap_instance_hits(RayBatch& b) const {
  for (uint32_t i = 0; i < b.count; ++i) {
    if (b.inst_id[i] == RTC_INVALID_GEOMETRY_ID) continue;
    uint32_t k = b.inst_id[i] - instance_base_;
    b.geom_id[i] += shapes_->prototypes[shapes_->instances[k].prototype].first;
    b.inst_id[i] = k;
  }
}

void RayStream::run_intersect(RayBatch& b, RayKind kind) {
  RTCIntersectContext ctx;
  rtcInitIntersectContext(&ctx);
  ctx.flags = kind == RayKind::Camera ? RTC_INTERSECT_CONTEXT_FLAG_COHERENT : RTC_INTERSECT_CONTEXT_FLAG_INCOHERENT;
  switch (backend_) {
    case RayBackend::StreamNp: {
      // Embree writes hits in place: misses must read as invalid already.
      // The other back ends reset their own AoS copies.
      for (uint32_t i = 0; i < b.count; ++i) b.geom_id[i] = b.inst_id[i] = RTC_INVALID_GEOMETRY_ID;
      RTCRayHitNp r = soa_view(b);
      rtcIntersectNp(scene_, &ctx, &r, b.count);
      break;
    }
    case RayBackend::Stream1M: {
      aos_.resize(b.count);
      for (uint32_t i = 0; i < b.count; ++i) {
        aos_[i].ray = aos_ray(b, i);
        aos_[i].hit.geomID = aos_[i].hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
      }
      rtcIntersect1M(scene_, &ctx, aos_.data(), b.count, sizeof(RTCRayHit));
      for (uint32_t i = 0; i < b.count; ++i) store_hit(b, i, aos_[i].ray, aos_[i].hit);
      break;
    }
    case RayBackend::Single: {
      for (uint32_t i = 0; i < b.count; ++i) {
        RTCRayHit rh;
        rh.ray = aos_ray(b, i);
        rh.hit.geomID = rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
        rtcIntersect1(scene_, &ctx, &rh);
        store_hit(b, i, rh.ray, rh.hit);
      }
      break;
    }
    case RayBackend::Packet16: {
      for (uint32_t base = 0; base < b.count; base += 16) {
        alignas(64) RTCRayHit16 p;
        alignas(64) int valid[16];
        load_packet(p.ray, b, base, valid);
        for (int k = 0; k < 16; ++k) p.hit.geomID[k] = p.hit.instID[0][k] = RTC_INVALID_GEOMETRY_ID;
        rtcIntersect16(valid, scene_, &ctx, &p);
        for (uint32_t k = 0; k < 16 && base + k < b.count; ++k) {
          uint32_t i = base + k;
          b.tfar[i] = p.ray.tfar[k];
          b.ng_x[i] = p.hit.Ng_x[k], b.ng_y[i] = p.hit.Ng_y[k], b.ng_z[i] = p.hit.Ng_z[k];
          b.u[i] = p.hit.u[k], b.v[i] = p.hit.v[k];
          b.prim_id[i] = p.hit.primID[k], b.geom_id[i] = p.hit.geomID[k], b.inst_id[i] = p.hit.instID[0][k];
        }
      }
      break;
    }
  }
}

void RayStream::occluded(RayBatch& b) {
  if (b.count == 0) return;
  if (counters_) counters_->shadow += b.count;
  if (dump_) dump_->write(RayKind::Shadow, b);
  if (!timing_ && !trace_) return run_occluded(b);
  const auto t0 = TraceClock::now();
  run_occluded(b);
  record(RayKind::Shadow, b.count, t0, TraceClock::now());
}

void RayStream::record(RayKind kind, uint32_t count, TraceClock::time_point t0, TraceClock::time_point t1) {
  if (timing_) seconds_[size_t(kind)] += std::chrono::duration<double>(t1 - t0).count();
  if (!trace_) return;
  static const char* names[] = {"camera rays", "extension rays", "light rays", "shadow rays"};
  trace_->span(names[size_t(kind)], TraceCategory::Rays, t0, t1, count);
  trace_->counter(trace_->rays_per_query_name(), t0, count);
  if (kind != RayKind::Shadow) trace_->counter(trace_->paths_alive_name(), t0, count);  // one ray per live path
}

void RayStream::run_occluded(RayBatch& b) {
  RTCIntersectContext ctx;
  rtcInitIntersectContext(&ctx);
  ctx.flags = RTC_INTERSECT_CONTEXT_FLAG_INCOHERENT;
  switch (backend_) {
    case RayBackend::StreamNp: {
      RTCRayHitNp r = soa_view(b);
      rtcOccludedNp(scene_, &ctx, &r.ray, b.count);
      break;
    }
    case RayBackend::Stream1M: {
      aos_rays_.resize(b.count);
      for (uint32_t i = 0; i < b.count; ++i) aos_rays_[i] = aos_ray(b, i);
      rtcOccluded1M(scene_, &ctx, aos_rays_.data(), b.count, sizeof(RTCRay));
      for (uint32_t i = 0; i < b.count; ++i) b.tfar[i] = aos_rays_[i].tfar;
      break;
    }
    case RayBackend::Single: {
      for (uint32_t i = 0; i < b.count; ++i) {
        RTCRay r = aos_ray(b, i);
        rtcOccluded1(scene_, &ctx, &r);
        b.tfar[i] = r.tfar;
      }
      break;
    }
    case RayBackend::Packet16: {
      for (uint32_t base = 0; base < b.count; base += 16) {
        alignas(64) RTCRay16 p;
        alignas(64) int valid[16];
        load_packet(p, b, base, valid);
        rtcOccluded16(valid, scene_, &ctx, &p);
        for (uint32_t k = 0; k < 16 && base + k < b.count; ++k) b.tfar[base + k] = p.tfar[k];
      }
      break;
    }
  }
}

}  // namespace lantern
