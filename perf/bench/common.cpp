#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <sstream>

#include "bench.h"

namespace bench {

std::shared_ptr<lantern::Scene> load(const Common& c, const std::string& scene) {
  lantern::LoadOptions lo;
  lo.warn = [](const std::string&) {};
  return lantern::load_scene(c.scenes_dir + "/" + scene + ".pbrt", lo);
}

lantern::RenderOptions scene_options(const Common& c, const lantern::Scene& scene, const std::string& integrator) {
  lantern::RenderOptions o;
  o.integrator = lantern::parse_integrator(integrator);
  o.maxdepth = lantern::scene_settings(scene).maxdepth;
  if (lantern::merges_vertices(lantern::parse_integrator(integrator))) o.wave_size = 16384;  // as the CLI (docs/vcm.md)
  o.threads = c.threads;
  return o;
}

lantern::RenderStats render_stats(const lantern::Scene& scene, lantern::RenderOptions o) {
  return lantern::render(scene, o).stats;
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v.empty() ? 0.0 : v.size() % 2 ? v[v.size() / 2] : 0.5 * (v[v.size() / 2 - 1] + v[v.size() / 2]);
}

std::string fmt(double v, int digits) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*g", digits, v);
  return buf;
}

void Table::print() const {
  auto line = [](const std::vector<std::string>& cells) {
    std::string s = "|";
    for (const auto& c : cells) s += " " + c + " |";
    std::puts(s.c_str());
  };
  line(header);
  line(std::vector<std::string>(header.size(), "---"));
  for (const auto& r : rows) line(r);
  std::puts("");
}

void Table::save_csv(const Common& c, const std::string& name) const {
  if (c.out_dir.empty()) return;
  std::filesystem::create_directories(c.out_dir);
  std::ofstream f(c.out_dir + "/" + name + ".csv");
  auto line = [&](const std::vector<std::string>& cells) {
    for (size_t i = 0; i < cells.size(); ++i) f << (i ? "," : "") << cells[i];
    f << "\n";
  };
  line(header);
  for (const auto& r : rows) line(r);
}

}  // namespace bench
