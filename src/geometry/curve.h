// pbrt's curves, traced by Embree's native curve primitives. Every curve is
// held as cubic Bézier segments (pbrt's B-spline and quadratic bases are
// converted at load, as pbrt-v4 does), four control points each with the
// radius in the fourth component, so the segment's u is pbrt's.
//
// pbrt intersects its "flat" and "cylinder" curves as ribbons that face the
// ray, and shades a "cylinder" with the normal a round fibre would have at
// that offset; Embree's flat curves are exactly such ray-facing ribbons. A
// "ribbon" curve follows the normals it is given: Embree's normal-oriented
// curves.
#pragma once

#include <glm/vec4.hpp>
#include <vector>

#include "math/common.h"

namespace lantern {

enum class CurveType : uint8_t { Flat, Cylinder, Ribbon };

// Consecutive Shape "curve" directives of one type and material share one
// set (one Embree geometry): a fur of 100k strands is not 100k geometries.
struct CurveSet {
  CurveType type = CurveType::Flat;
  std::vector<glm::vec4> control;    // 4 per segment: position and radius
  std::vector<Vec3> normals;         // Ribbon: 4 per segment
  std::vector<Vec2> u_range;         // per segment: its span of the whole curve's u

  uint32_t segments() const { return uint32_t(u_range.size()); }
  // pbrt's u along the whole curve at a segment's own u.
  float curve_u(uint32_t segment, float u) const {
    const Vec2 span = u_range[segment];
    return span.x + (span.y - span.x) * u;
  }
};

// A segment's position, derivative and radius at u.
struct CurveFrame {
  Vec3 p, dpdu;
  float radius;
};
CurveFrame curve_eval(const CurveSet& c, uint32_t segment, float u);

// The control points of pbrt's curve (basis "bezier" or "bspline", degree 2
// or 3) as cubic Bézier segments; empty when P has the wrong number of
// points for the basis and degree. Each entry of the result is one segment.
struct BezierSegment {
  Vec3 cp[4];
};
std::vector<BezierSegment> bezier_segments(const std::vector<Vec3>& P, bool bspline, int degree);

// The curve point of a hit at segment `segment`, parameter u, reached by
// the ray o + t d (in the curve set's own space). uv is pbrt's: u along the
// whole curve, v across it, and v = (h + 1) / 2 where h in [-1, 1] is the
// hit's offset from the axis that pbrt's hair BSDF reads. dpdu is the unit
// tangent. ng_embree: Embree's geometric normal (used for ribbons).
struct SurfacePoint;
SurfacePoint curve_point(const CurveSet& c, uint32_t segment, float u, const Vec3& o, const Vec3& d, float t,
                         const Vec3& ng_embree);

}  // namespace lantern
