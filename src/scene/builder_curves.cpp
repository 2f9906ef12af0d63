// Shape "curve", with pbrt-v4's parameters and defaults: P, basis
// ("bezier" or "bspline"), degree (2 or 3), type ("flat", "cylinder" or
// "ribbon"), N (ribbons: one normal per segment end), width or width0 and
// width1 (interpolated along the whole curve); splitdepth is accepted.
#include "scene/builder.h"

namespace lantern {

using pbrt::ParamSet;

namespace {

CurveType curve_type(const ParamSet& ps) {
  const std::string t = ps.get_string("type", "flat");
  if (t == "flat") return CurveType::Flat;
  if (t == "cylinder") return CurveType::Cylinder;
  if (t == "ribbon") return CurveType::Ribbon;
  ps.fail(*ps.find("type"), "curve type \"" + printable(t) + "\" is unknown; expected flat, cylinder or ribbon");
}

float width_param(const ParamSet& ps, const char* name, float def) {
  float w = ps.get_float(name, def);
  if (!(w >= 0.f) || !std::isfinite(w)) ps.fail(*ps.find(name), std::string("\"") + name + "\" must be finite and at least 0");
  return w;
}

// The set the next curve goes into: the last geometry's, when it is a set
// of the same type and material in the same scope (the world, or
// the object being defined) and nothing (alpha) sets it apart; otherwise a
// new one.
bool can_join(const ShapePools& s, const CurveSet& c, MaterialHandle m, bool last_in_scope, bool alpha) {
  if (alpha || !last_in_scope || s.geometries.empty()) return false;
  const Geometry& g = s.geometries.back();
  if (g.kind != ShapeKind::Curve || g.material.bits != m.bits || g.alpha >= 0) return false;
  const CurveSet& last = s.curves[g.index];
  return last.type == c.type;
}

}  // namespace

void SceneBuilder::add_curve(const ParamSet& ps, const GraphicsState& gs) {
  if (gs.area_light)
    ps.fail("a curve cannot emit light (nor can it in pbrt-v4); use another shape inside the AreaLightSource");
  const std::vector<Vec3> P = ps.get_point3s("P");
  if (P.empty()) ps.fail("\"point3 P\" is missing");
  for (const Vec3& p : P)
    if (!is_finite(p)) ps.fail(*ps.find("P"), "\"P\" has a value that is not finite");
  const std::string basis = ps.get_string("basis", "bezier");
  if (basis != "bezier" && basis != "bspline")
    ps.fail(*ps.find("basis"), "curve basis \"" + printable(basis) + "\" is unknown; expected bezier or bspline");
  const int degree = ps.get_int("degree", 3);
  if (degree != 2 && degree != 3) ps.fail(*ps.find("degree"), "curve degree must be 2 or 3");
  const std::vector<BezierSegment> segs = bezier_segments(P, basis == "bspline", degree);
  if (segs.empty()) {
    const bool bs = basis == "bspline";
    ps.fail(*ps.find("P"), "\"P\" has " + std::to_string(P.size()) + " points; a degree-" + std::to_string(degree) + " " +
                               basis + " curve needs " +
                               (bs ? "at least " + std::to_string(degree + 1)
                                   : std::to_string(degree) + "n + 1 for n >= 1 segments"));
  }
  CurveSet c;
  c.type = curve_type(ps);
  ps.find("splitdepth");  // pbrt's own refinement; Embree's is fixed (accel/embree_scene.cpp)
  const float width = width_param(ps, "width", 1.f);
  const float w0 = width_param(ps, "width0", width), w1 = width_param(ps, "width1", width);
  const size_t n = segs.size();
  std::vector<Vec3> N = ps.get_point3s("N");
  if (c.type == CurveType::Ribbon) {
    if (N.empty()) ps.fail("a ribbon curve needs \"normal N\": one normal at each end of each segment");
    if (N.size() != n + 1)
      ps.fail(*ps.find("N"), "\"N\" has " + std::to_string(N.size()) + " normals; this curve's " + std::to_string(n) +
                                 " segments need " + std::to_string(n + 1));
  } else if (!N.empty()) {
    warn(ps.find("N")->where, "curve normals are used only by \"ribbon\" curves; ignored");
  }
  // Into render space. pbrt keeps the width in the curve's own space; a
  // non-uniform scale cannot keep a round cross-section, so the width takes
  // the transform's mean scale (the cube root of its determinant).
  const glm::dmat4& M = gs.render_from_object;
  const double det = glm::determinant(glm::dmat3(M));
  if (!(std::fabs(det) > 0.0)) ps.fail("the curve's transform is singular");
  const float scale = float(std::cbrt(std::fabs(det)));
  const glm::dmat3 normal_m = glm::transpose(glm::inverse(glm::dmat3(M)));
  for (size_t i = 0; i < n; ++i) {
    const float r0 = 0.5f * scale * glm::mix(w0, w1, float(i) / float(n));
    const float r1 = 0.5f * scale * glm::mix(w0, w1, float(i + 1) / float(n));
    for (int k = 0; k < 4; ++k) {
      Vec3 p = Vec3(M * glm::dvec4(glm::dvec3(segs[i].cp[k]), 1.0));
      if (!is_finite(p)) ps.fail("the curve's position under the current transform exceeds single precision");
      c.control.emplace_back(p, r0 + (r1 - r0) * float(k) / 3.f);
      if (c.type == CurveType::Ribbon) {
        Vec3 a = Vec3(normal_m * glm::dvec3(N[i])), b = Vec3(normal_m * glm::dvec3(N[i + 1]));
        c.normals.push_back(glm::mix(a, b, float(k) / 3.f));
      }
    }
    c.u_range.emplace_back(float(i) / float(n), float(i + 1) / float(n));
  }
  ShapePools& s = scene_.shapes;
  const MaterialHandle m = gs.material ? *gs.material : default_material();
  const bool last_in_scope = object_ ? s.prototypes[object_->prototype].count > 0
                                     : !s.in_prototype.empty() && !s.in_prototype.back();
  if (can_join(s, c, m, last_in_scope, ps.has("alpha"))) {
    CurveSet& last = s.curves[s.geometries.back().index];
    if (!last.normals.empty()) last.normals.pop_back();  // the padding
    last.control.insert(last.control.end(), c.control.begin(), c.control.end());
    last.normals.insert(last.normals.end(), c.normals.begin(), c.normals.end());
    last.u_range.insert(last.u_range.end(), c.u_range.begin(), c.u_range.end());
    if (c.type == CurveType::Ribbon) last.normals.emplace_back(0.f);
    return;
  }
  if (c.type == CurveType::Ribbon) c.normals.emplace_back(0.f);  // Embree reads 16 bytes per normal
  s.curves.push_back(std::move(c));
  s.geometries.push_back({ShapeKind::Curve, uint32_t(s.curves.size() - 1), m, -1, -1, {}});
  note_geometry();
}

}  // namespace lantern
