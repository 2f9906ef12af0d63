// Transformations that change while the shutter is open (motion blur).
//
// pbrt's AnimatedTransform gives a transform at two times (TransformTimes,
// default 0 and 1) and moves between them by decomposing each into
// translation, rotation and scale, M = T R S (the polar decomposition,
// Shoemake and Duff 1992, "Matrix animation and polar decomposition"),
// interpolating T and S linearly and R along the shorter great arc of the
// unit quaternions (slerp); before the first time the first transform
// holds, after the second the second.
//
// Embree traces moving instances by interpolating matrices linearly
// between equally spaced time steps. A MotionPath holds such steps, each
// exactly pbrt's interpolated transform at its time, with as many steps as
// the rotation needs: between two steps a rotation by angle a is replaced
// by the chord, shrinking what turns by at most 1 - cos(a / 2) of its
// distance from the axis; kMaxStepAngle keeps that below 4e-5 (at a 1 m
// radius, 40 microns). Shading asks the same MotionPath for the transform
// at a ray's time, so what is shaded is what Embree intersected.
#pragma once

#include <vector>

#include "math/common.h"

namespace lantern {

// pbrt's interpolation of two transforms at u in [0, 1] (u = 0: m0).
glm::dmat4 interpolate_transform(const glm::dmat4& m0, const glm::dmat4& m1, double u);

// The rotation between the polar decompositions' rotations of m0 and m1,
// in radians along the shorter arc.
double rotation_angle(const glm::dmat4& m0, const glm::dmat4& m1);

inline constexpr double kMaxStepAngle = 0.0175;  // radians (1 degree)
inline constexpr int kMaxMotionSteps = 129;      // Embree's RTC_MAX_TIME_STEP_COUNT

struct MotionPath {
  std::vector<Mat4> steps;  // at u = i / (steps.size() - 1); at least 2

  // The matrix at u in [0, 1], as Embree interpolates between the steps.
  Mat4 at(float u) const {
    const float x = glm::clamp(u, 0.f, 1.f) * float(steps.size() - 1);
    const size_t i = std::min(size_t(x), steps.size() - 2);
    const float f = x - float(i);
    return (1.f - f) * steps[i] + f * steps[i + 1];
  }
};

// The steps that follow pbrt's interpolation from m0 to m1 (see above).
MotionPath motion_path(const glm::dmat4& m0, const glm::dmat4& m1);

// The shutter in pbrt's terms: a camera sample's time lies uniformly in
// [open, close]; transforms move over [start, end] (TransformTimes). unit()
// is where a time falls on the transforms' [0, 1] (clamped: a transform
// holds still before start and after end).
struct ShutterTimes {
  float open = 0.f, close = 1.f;
  float start = 0.f, end = 1.f;
  float time(float u) const { return open + u * (close - open); }
  float unit(float t) const {
    if (!(end > start)) return t <= start ? 0.f : 1.f;
    return glm::clamp((t - start) / (end - start), 0.f, 1.f);
  }
};

}  // namespace lantern
