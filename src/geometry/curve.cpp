#include "geometry/curve.h"

#include "math/frame.h"
#include "geometry/surface.h"

namespace lantern {


namespace {

template <class T>
T bezier(const T& a, const T& b, const T& c, const T& d, float u) {
  float s = 1.f - u;
  return (s * s * s) * a + (3.f * s * s * u) * b + (3.f * s * u * u) * c + (u * u * u) * d;
}

template <class T>
T bezier_derivative(const T& a, const T& b, const T& c, const T& d, float u) {
  float s = 1.f - u;
  return 3.f * ((s * s) * (b - a) + (2.f * s * u) * (c - b) + (u * u) * (d - c));
}

// A unit vector perpendicular to unit v.
Vec3 any_perpendicular(const Vec3& v) {
  Vec3 s, t;
  coordinate_system(v, s, t);
  return s;
}

}  // namespace

CurveFrame curve_eval(const CurveSet& c, uint32_t segment, float u) {
  const glm::vec4* q = &c.control[4 * size_t(segment)];
  glm::vec4 p = bezier(q[0], q[1], q[2], q[3], u);
  glm::vec4 dp = bezier_derivative(q[0], q[1], q[2], q[3], u);
  return {Vec3(p), Vec3(dp), p.w};
}

// The conversions are the change of basis between uniform B-splines (or
// quadratic Béziers) and cubic Béziers: the same polynomial pieces, so u
// within a segment is unchanged (Farin, Curves and Surfaces for CAGD, ch. 5
// and 7).
std::vector<BezierSegment> bezier_segments(const std::vector<Vec3>& P, bool bspline, int degree) {
  std::vector<BezierSegment> out;
  const size_t n = P.size();
  auto elevate = [](const Vec3& a, const Vec3& b, const Vec3& c) {
    return BezierSegment{{a, a + (2.f / 3.f) * (b - a), c + (2.f / 3.f) * (b - c), c}};
  };
  if (!bspline && degree == 3) {
    if (n < 4 || (n - 1) % 3 != 0) return out;
    for (size_t i = 0; i + 3 < n; i += 3) out.push_back({{P[i], P[i + 1], P[i + 2], P[i + 3]}});
  } else if (!bspline && degree == 2) {
    if (n < 3 || (n - 1) % 2 != 0) return out;
    for (size_t i = 0; i + 2 < n; i += 2) out.push_back(elevate(P[i], P[i + 1], P[i + 2]));
  } else if (bspline && degree == 3) {
    if (n < 4) return out;
    for (size_t i = 0; i + 3 < n; ++i) {
      const Vec3 &p0 = P[i], &p1 = P[i + 1], &p2 = P[i + 2], &p3 = P[i + 3];
      out.push_back({{(p0 + 4.f * p1 + p2) / 6.f, (2.f * p1 + p2) / 3.f, (p1 + 2.f * p2) / 3.f, (p1 + 4.f * p2 + p3) / 6.f}});
    }
  } else if (bspline && degree == 2) {
    if (n < 3) return out;
    for (size_t i = 0; i + 2 < n; ++i) out.push_back(elevate(0.5f * (P[i] + P[i + 1]), P[i + 1], 0.5f * (P[i + 1] + P[i + 2])));
  }
  return out;
}

SurfacePoint curve_point(const CurveSet& c, uint32_t segment, float u, const Vec3& o, const Vec3& d, float t,
                         const Vec3& ng_embree) {
  const CurveFrame f = curve_eval(c, segment, u);
  const float dl = glm::length(d);
  const Vec3 wo = dl > 0.f ? -d / dl : Vec3(0, 0, 1);
  float tl = glm::length(f.dpdu);
  const Vec3 T = tl > 0.f ? f.dpdu / tl : any_perpendicular(wo);
  // The ribbon pbrt intersects faces the ray: its normal is the direction
  // back along the ray, made perpendicular to the curve.
  Vec3 z0 = wo - glm::dot(wo, T) * T;
  float zl = glm::length(z0);
  z0 = zl > 1e-6f ? z0 / zl : any_perpendicular(T);
  const Vec3 p = o + t * d;
  const float r = max_num(f.radius, 1e-30f);
  Vec3 n = z0, across = glm::cross(z0, T);
  if (c.type == CurveType::Ribbon) {
    // Embree's normal, on the side of the normals the curve was given.
    const Vec3* nq = &c.normals[4 * size_t(segment)];
    Vec3 given = bezier(nq[0], nq[1], nq[2], nq[3], u);
    float nl = glm::length(ng_embree);
    n = nl > 0.f && std::isfinite(nl) ? ng_embree / nl : given;
    if (glm::dot(n, given) < 0.f) n = -n;
    Vec3 b = glm::cross(n, T);
    float bl = glm::length(b);
    across = bl > 0.f ? b / bl : across;
  }
  // h: the hit's signed offset from the axis across the curve, in radii.
  float h = glm::clamp(glm::dot(p - f.p, across) / r, -1.f, 1.f);
  // pbrt shades a "cylinder" curve with its normal turned about the curve
  // in proportion to h, up to 90 degrees at the edges: towards the side the
  // hit is on (pbrt-v4 turns it away; docs/shapes.md).
  if (c.type == CurveType::Cylinder) {
    const float a = 0.5f * kPi * h;
    n = std::sin(a) * across + std::cos(a) * z0;
  }
  SurfacePoint sp;
  sp.p = p;
  sp.ng = sp.ns = n;
  sp.uv = Vec2(c.curve_u(segment, u), 0.5f * (h + 1.f));
  sp.dpdu = T;
  // pbrt bounds a curve hit's error by the curve's width in each axis: rays
  // leave a fibre from one to two widths off its ribbon, so that a ray
  // continuing through it does not meet it again. Negative: a surface that
  // faces the ray (offset_ray_origin, vertex_cos). A ribbon is a surface
  // like any other, offset by a tenth of its width.
  const float normal_l1 = std::fabs(n.x) + std::fabs(n.y) + std::fabs(n.z);
  sp.error_scale = c.type == CurveType::Ribbon
                       ? max_num(max_abs_component(p), 0.1f * r / kRayOffsetScale)
                       : -max_num(max_abs_component(p), 2.f * r * normal_l1 / kRayOffsetScale);
  return sp;
}

}  // namespace lantern
