// Small value types and constants shared by every part of the renderer.
#pragma once

#include "math/max_num.h"
#include "math/spectrum.h"

#include <glm/glm.hpp>

#include <cmath>
#include <cstdint>
#include <limits>

namespace lantern {

using Vec2 = glm::vec2;
using Vec3 = glm::vec3;
using Vec4 = glm::vec4;
using Mat4 = glm::mat4;

inline constexpr float kPi = 3.14159265358979323846f;
inline constexpr float kInvPi = 0.31830988618379067154f;
inline constexpr float kInv2Pi = 0.15915494309189533577f;
inline constexpr float kInv4Pi = 0.07957747154594766788f;
inline constexpr float kInfinity = std::numeric_limits<float>::infinity();
inline constexpr float kOneMinusEpsilon = 0x1.fffffep-1f;

inline float sqr(float x) { return x * x; }
inline float safe_sqrt(float x) { return std::sqrt(max_num(0.f, x)); }
inline float max_component(const Vec3& v) { return max_num(v.x, max_num(v.y, v.z)); }
inline float max_abs_component(const Vec3& v) {
  return max_num(std::fabs(v.x), max_num(std::fabs(v.y), std::fabs(v.z)));
}
inline bool is_finite(const Vec3& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

// Power heuristic with beta = 2 (Veach 1997, eq. 9.13), written for counts
// of one sample per strategy.
inline float power_heuristic(float pdf_a, float pdf_b) {
  if (std::isinf(pdf_a)) return 1.f;
  float a = pdf_a * pdf_a, b = pdf_b * pdf_b;
  return a + b > 0.f ? a / (a + b) : 0.f;
}

}  // namespace lantern
