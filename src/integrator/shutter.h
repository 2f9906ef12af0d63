// When in the shutter a camera sample sees the scene (math/motion.h): a
// number in [0, 1] along the transforms' motion, shared by the sample's
// eye and light subpaths and carried by every ray they trace; and where
// on the lens.
#pragma once

#include "sampler/dimensions.h"
#include "sampler/sampler.h"
#include "scene/scene.h"

namespace lantern {

// Drawn uniformly over [shutteropen, shutterclose] from the sample's own
// dimension, as pbrt's cameras draw it, and mapped onto the transforms'
// [start, end] (TransformTimes). A scene where nothing moves draws
// nothing: its samples read the dimensions they always did.
inline float sample_time(const Scene& scene, const PathSampler& s, int maxdepth) {
  if (!scene.moving()) return 0.f;
  const uint32_t d = uint32_t(maxdepth);
  const ShutterTimes& shutter = scene.camera.shutter;
  return shutter.unit(shutter.time(s.get1d(dims::shutter(dims::vertex(d + 2), d))));
}

// The lens's two numbers, for a camera ray or a connection to the camera:
// drawn only where the camera has a lens (a pinhole reads none).
inline Vec2 lens_numbers(const Camera& camera, const PathSampler& s, uint32_t dimension) {
  return camera.reads_lens_numbers() ? s.get2d(dimension) : Vec2(0.5f);
}

}  // namespace lantern
