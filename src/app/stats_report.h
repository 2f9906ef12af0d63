// The render's measurements for people (a few lines on stderr) and for
// tools (`--stats FILE.json`).
#pragma once

#include <nlohmann/json.hpp>
#include <string>

#include "film/image_metrics.h"
#include "lantern/render.h"
#include "lantern/scene.h"

namespace lantern {

struct RunInfo {
  std::string scene, integrator, output, ray_backend;
  int width = 0, height = 0, wave_size = 0;
  double load_seconds = 0.0;  // parsing, geometry and the BVH build
  SceneInfo scene_info;
  SamplerSettings scene_sampler, sampler;  // what the scene asked for, what was used
  std::string scene_light_sampler;
};

nlohmann::json stats_json(const RunInfo& run, const RenderStats& stats);
// Stage shares and subpath summary; called only for timed renders.
void print_stage_summary(const RenderStats& stats);
// The metrics of `lantern compare` (and Python's lantern.compare), by name;
// an infinite PSNR (identical images) is null.
nlohmann::json comparison_json(const ImageComparison& m);
// Peak resident set size of this process, in bytes.
size_t peak_rss_bytes();

}  // namespace lantern
