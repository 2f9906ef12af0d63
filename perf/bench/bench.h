// Shared pieces of the benchmark drivers: rendering with stats, tables, CSV.
#pragma once

#include <fstream>
#include <string>
#include <vector>

#include "lantern/render.h"
#include "lantern/scene.h"

namespace bench {

struct Common {
  std::string scenes_dir = "scenes";
  std::string out_dir;  // CSV files go here when set
  int threads = 0;
};

std::shared_ptr<lantern::Scene> load(const Common& c, const std::string& scene);
// Render options as the command line would set them for this scene: its
// own maxdepth (references are rendered with it), the chosen threads.
lantern::RenderOptions scene_options(const Common& c, const lantern::Scene& scene, const std::string& integrator);
lantern::RenderStats render_stats(const lantern::Scene& scene, lantern::RenderOptions o);
double median(std::vector<double> v);

// A table printed as Markdown and optionally saved as CSV.
struct Table {
  std::vector<std::string> header;
  std::vector<std::vector<std::string>> rows;
  void print() const;
  void save_csv(const Common& c, const std::string& name) const;
};
std::string fmt(double v, int digits = 3);

int throughput(const Common& c, const std::vector<std::string>& scenes, int spp, int width, int height);
int backends(const Common& c, const std::string& scene, const std::string& integrator, int spp, int rounds);
int scaling(const Common& c, const std::string& scene, const std::string& integrator, int spp);
int convergence(const Common& c, const std::string& scene, const std::string& reference, double max_seconds,
                const std::vector<std::string>& integrators);

}  // namespace bench
