#include "math/motion.h"

#include <glm/gtc/quaternion.hpp>

#include <algorithm>
#include <cmath>

namespace lantern {
namespace {

struct Decomposed {
  glm::dvec3 translation;
  glm::dquat rotation;
  glm::dmat3 stretch;  // symmetric: M's upper 3x3 = R S
};

// The polar decomposition of the upper 3x3 by Newton's iteration
// R <- (R + R^-T) / 2 (Higham 1986), which converges quadratically to the
// orthogonal factor of a non-singular matrix. A reflection (negative
// determinant) is kept in S, so that R stays a rotation a quaternion can
// hold.
Decomposed decompose(const glm::dmat4& m) {
  Decomposed d;
  d.translation = glm::dvec3(m[3]);
  const glm::dmat3 a(m);
  if (!(std::fabs(glm::determinant(a)) > 1e-300)) {  // flattened to a plane or less: no rotation to find
    d.rotation = glm::dquat(1.0, 0.0, 0.0, 0.0);
    d.stretch = a;
    return d;
  }
  const double sign = glm::determinant(a) < 0.0 ? -1.0 : 1.0;
  glm::dmat3 r = sign * a;
  for (int i = 0; i < 100; ++i) {
    const glm::dmat3 next = 0.5 * (r + glm::transpose(glm::inverse(r)));
    double change = 0.0;
    for (int c = 0; c < 3; ++c)
      for (int k = 0; k < 3; ++k) change = std::max(change, std::fabs(next[c][k] - r[c][k]));
    r = next;
    if (change < 1e-14) break;
  }
  d.rotation = glm::normalize(glm::quat_cast(r));
  d.stretch = glm::transpose(r) * a;
  return d;
}

// The shorter arc: q and -q are the same rotation.
glm::dquat toward(const glm::dquat& from, glm::dquat q) { return glm::dot(from, q) < 0.0 ? -q : q; }

}  // namespace

glm::dmat4 interpolate_transform(const glm::dmat4& m0, const glm::dmat4& m1, double u) {
  if (u <= 0.0) return m0;
  if (u >= 1.0) return m1;
  const Decomposed a = decompose(m0), b = decompose(m1);
  const glm::dquat q1 = toward(a.rotation, b.rotation);
  // Nearly equal rotations: slerp's sin(angle) would vanish; normalised
  // linear interpolation is then exact to rounding.
  const glm::dquat q = glm::dot(a.rotation, q1) > 0.9999995 ? glm::normalize(glm::lerp(a.rotation, q1, u))
                                                              : glm::slerp(a.rotation, q1, u);
  const glm::dmat3 s = (1.0 - u) * a.stretch + u * b.stretch;
  glm::dmat4 m(glm::mat3_cast(q) * s);
  m[3] = glm::dvec4((1.0 - u) * a.translation + u * b.translation, 1.0);
  return m;
}

double rotation_angle(const glm::dmat4& m0, const glm::dmat4& m1) {
  const glm::dquat a = decompose(m0).rotation, b = decompose(m1).rotation;
  return 2.0 * std::acos(std::min(1.0, std::fabs(glm::dot(a, b))));
}

MotionPath motion_path(const glm::dmat4& m0, const glm::dmat4& m1) {
  const double angle = rotation_angle(m0, m1);
  const int segments = std::clamp(int(std::ceil(angle / kMaxStepAngle)), 1, kMaxMotionSteps - 1);
  MotionPath path;
  path.steps.reserve(size_t(segments) + 1);
  for (int i = 0; i <= segments; ++i) path.steps.push_back(Mat4(interpolate_transform(m0, m1, double(i) / segments)));
  return path;
}

}  // namespace lantern
