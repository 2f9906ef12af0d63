// bdpt's pilot (integrator/light_subpath_rate.h) run on one thread and on
// all of them, for the tests that its choices do not depend on the threads.
#pragma once

#include <tbb/global_control.h>

#include <utility>

#include "integrator/light_subpath_rate.h"
#include "integrator/render_settings.h"
#include "light/light_sampler.h"
#include "scene/scene.h"

namespace lantern {

inline std::pair<LightSubpathRateChoice, LightSubpathRateChoice> pilots_on_one_and_all_threads(const Scene& scene,
                                                                                               const RenderOptions& o) {
  const LightSampler light_sampler(scene.lights, scene.shapes, scene.textures, LightSamplerKind::Bvh);
  const BdptSettings bs = bdpt_settings(scene, o, image_region(scene, o), 0);
  LightSubpathRateChoice one;
  {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 1);
    one = choose_light_subpath_rate(scene, light_sampler, bs, RayBackend::StreamNp);
  }
  return {one, choose_light_subpath_rate(scene, light_sampler, bs, RayBackend::StreamNp)};
}

}  // namespace lantern
