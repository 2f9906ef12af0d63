// The render's measurements for people (a few lines on stderr) and for
// tools (`--stats FILE.json`).
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "film/image_metrics.h"
#include "lantern/render.h"
#include "lantern/scene.h"

namespace lantern {

// A loading stage as the loader names it ("parsing ...", "reading 25 PLY
// meshes", "building the BVH"): when it ended, the resident memory then and
// the process's peak so far (which stage reached the peak).
struct LoadPhase {
  std::string stage;
  double end_seconds = 0.0;
  size_t rss_bytes = 0, peak_rss_bytes = 0;
};

struct RunInfo {
  std::string scene, integrator, output, ray_backend;
  int width = 0, height = 0, wave_size = 0;
  double load_seconds = 0.0;  // parsing, geometry and the BVH build
  SceneInfo scene_info;
  SamplerSettings scene_sampler, sampler;  // what the scene asked for, what was used
  std::string scene_light_sampler;
  std::vector<LoadPhase> load_phases;
};

nlohmann::json stats_json(const RunInfo& run, const RenderStats& stats);
// Stage shares and subpath summary; called only for timed renders.
void print_stage_summary(const RenderStats& stats);
// The metrics of `lantern compare` (and Python's lantern.compare), by name;
// an infinite PSNR (identical images) is null.
nlohmann::json comparison_json(const ImageComparison& m);
// Peak and current resident set size of this process, in bytes.
size_t peak_rss_bytes();
size_t rss_bytes();

}  // namespace lantern
