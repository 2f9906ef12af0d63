// Shape "sphere", "cylinder" and "disk", with pbrt-v4's parameters and
// defaults. A full sphere under uniform scale is Embree's own sphere
// primitive; every other one, and every cylinder and disk, is an exact
// quadric (geometry/quadric.h).
#include "scene/builder.h"

namespace lantern {

using pbrt::ParamSet;

namespace {

float finite_param(const ParamSet& ps, const char* name, float def) {
  float v = ps.get_float(name, def);
  if (!std::isfinite(v)) ps.fail(*ps.find(name), std::string("\"") + name + "\" must be finite");
  return v;
}

float phi_max_param(const ParamSet& ps) {
  return glm::radians(glm::clamp(finite_param(ps, "phimax", 360.f), 0.f, 360.f));
}

}  // namespace

void SceneBuilder::add_quadric(const std::string& type, const ParamSet& ps, const GraphicsState& gs) {
  const Mat4 M(gs.render_from_object);
  const bool flip = gs.reverse_orientation != (glm::determinant(glm::mat3(M)) < 0.f);
  float r = finite_param(ps, "radius", 1.f);
  if (!(r > 0.f)) ps.fail(*ps.find("radius"), "\"radius\" must be positive");
  Quadric q;
  q.radius = r;
  q.flip_normal = flip;
  q.phi_max = phi_max_param(ps);
  if (type == "sphere") {
    float z0 = finite_param(ps, "zmin", -r), z1 = finite_param(ps, "zmax", r);
    q.z_min = glm::clamp(min_num(z0, z1), -r, r);
    q.z_max = glm::clamp(max_num(z0, z1), -r, r);
    q.theta_z_min = std::acos(glm::clamp(q.z_min / r, -1.f, 1.f));
    q.theta_z_max = std::acos(glm::clamp(q.z_max / r, -1.f, 1.f));
    const float sx = glm::length(Vec3(M[0])), sy = glm::length(Vec3(M[1])), sz = glm::length(Vec3(M[2]));
    const bool uniform = sx > 0.f && std::fabs(sx - sy) <= 1e-4f * sx && std::fabs(sx - sz) <= 1e-4f * sx &&
                         std::fabs(glm::dot(Vec3(M[0]), Vec3(M[1]))) <= 1e-4f * sx * sy &&
                         std::fabs(glm::dot(Vec3(M[0]), Vec3(M[2]))) <= 1e-4f * sx * sz &&
                         std::fabs(glm::dot(Vec3(M[1]), Vec3(M[2]))) <= 1e-4f * sy * sz;
    if (uniform && q.z_min <= -r && q.z_max >= r && q.phi_max >= 2.f * kPi) {
      Sphere s{Vec3(M * Vec4(0, 0, 0, 1)), r * sx, flip, glm::inverse(M)};
      if (!is_finite(s.center) || !std::isfinite(s.radius)) ps.fail("the sphere's centre or radius is not finite");
      ShapePools& p = scene_.shapes;
      p.spheres.push_back(s);
      p.geometries.push_back({ShapeKind::Sphere, uint32_t(p.spheres.size() - 1), gs.material ? *gs.material : default_material(), -1, -1, {}});
      note_geometry();
      add_area_lights(uint32_t(p.geometries.size() - 1), 1, gs, ps);
      return;
    }
    q.kind = QuadricKind::Sphere;
  } else if (type == "cylinder") {
    float z0 = finite_param(ps, "zmin", -1.f), z1 = finite_param(ps, "zmax", 1.f);
    q.kind = QuadricKind::Cylinder;
    q.z_min = min_num(z0, z1);
    q.z_max = max_num(z0, z1);
  } else {  // disk
    q.kind = QuadricKind::Disk;
    q.z_min = q.z_max = finite_param(ps, "height", 0.f);
    q.inner_radius = finite_param(ps, "innerradius", 0.f);
    if (!(q.inner_radius >= 0.f) || !(q.inner_radius < r))
      ps.fail(*ps.find("innerradius"), "\"innerradius\" must be at least 0 and less than \"radius\"");
  }
  switch (finish_quadric(q, gs.render_from_object)) {
    case QuadricCheck::Ok: break;
    case QuadricCheck::Singular: ps.fail("the shape's transform is singular");
    case QuadricCheck::OutOfRange:
      ps.fail("the " + type + "'s size or position (its parameters under the current transform) exceeds single "
              "precision");
    case QuadricCheck::NoArea:
      warn(ps.where, "the " + type + " has no area (zmin = zmax, phimax = 0 or a vanishing size) and was skipped");
      return;
  }
  ShapePools& p = scene_.shapes;
  p.quadrics.push_back(q);
  p.geometries.push_back({ShapeKind::Quadric, uint32_t(p.quadrics.size() - 1), gs.material ? *gs.material : default_material(), -1, -1, {}});
  note_geometry();
  add_area_lights(uint32_t(p.geometries.size() - 1), 1, gs, ps);
}

}  // namespace lantern
