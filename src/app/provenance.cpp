#include "app/provenance.h"

#include <ctime>
#include <fstream>
#include <thread>

namespace lantern {

namespace {

std::string cpu_model() {
  std::ifstream in("/proc/cpuinfo");
  for (std::string line; std::getline(in, line);)
    if (line.rfind("model name", 0) == 0) {
      const size_t colon = line.find(':');
      if (colon != std::string::npos) return line.substr(line.find_first_not_of(" \t", colon + 1));
    }
  return "unknown";
}

// An argument as a shell would read it back: quoted when it holds
// anything but plain characters.
std::string quoted(const std::string& s) {
  if (!s.empty() && s.find_first_not_of("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789-_./=:,+@%") ==
                        std::string::npos)
    return s;
  std::string q = "'";
  for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

}  // namespace

Provenance provenance(int argc, char** argv) {
  Provenance p;
  p.cpu = cpu_model();
  p.cores = std::thread::hardware_concurrency();
  const std::time_t now = std::time(nullptr);
  char date[32];
  std::tm utc{};
  gmtime_r(&now, &utc);
  std::strftime(date, sizeof date, "%Y-%m-%dT%H:%M:%SZ", &utc);
  p.date = date;
  for (int i = 0; i < argc; ++i) p.command += (i ? " " : "") + quoted(argv[i]);
  return p;
}

std::string version_line() {
  return std::string("lantern ") + kBuildInfo.version + " (commit " + kBuildInfo.commit + ", " + kBuildInfo.build_type +
         ", " + kBuildInfo.compiler + ")";
}

nlohmann::json provenance_json(const Provenance& p) {
  return {{"version", kBuildInfo.version}, {"commit", kBuildInfo.commit}, {"build_type", kBuildInfo.build_type},
          {"compiler", kBuildInfo.compiler}, {"cpu", p.cpu}, {"cores", p.cores}, {"date", p.date},
          {"command", p.command}};
}

void add_provenance(ImageMetadata& md, const Provenance& p) {
  md.emplace_back("lantern:version", kBuildInfo.version);
  md.emplace_back("lantern:commit", kBuildInfo.commit);
  md.emplace_back("lantern:build", std::string(kBuildInfo.build_type) + ", " + kBuildInfo.compiler);
  md.emplace_back("lantern:cpu", p.cpu + " (" + std::to_string(p.cores) + " threads)");
  md.emplace_back("lantern:date", p.date);
  md.emplace_back("lantern:command", p.command);
}

namespace {

std::string budget(const RenderOptions& o) {
  std::string b = o.time_limit_seconds > 0 ? "time " + std::to_string(o.time_limit_seconds) + " s"
                                           : "spp " + std::to_string(o.spp);
  if (o.target_error > 0) b += ", target error " + std::to_string(o.target_error);
  else if (o.adaptive) b += o.time_limit_seconds > 0 ? ", adaptive" : ", adaptive (the mean)";
  return b;
}

std::string sampler(const RenderOptions& o) {
  std::string s = std::string(name(o.sampler.type)) + " (randomization " + o.sampler.randomization + ", seed " +
                  std::to_string(o.sampler.seed);
  if (o.sampler.type == SamplerKind::Stratified)
    s += ", " + std::to_string(o.sampler.xsamples) + "x" + std::to_string(o.sampler.ysamples) +
         (o.sampler.jitter ? " jittered" : "");
  return s + ")";
}

}  // namespace

nlohmann::json render_settings_json(const RenderOptions& o) {
  nlohmann::json j = {{"integrator", name(o.integrator)}, {"maxdepth", o.maxdepth},
                      {"seed", o.seed},                   {"budget", budget(o)},
                      {"sampler", sampler(o)},            {"light_sampler", name(o.light_sampler)},
                      {"mis", name(o.mis)},               {"colour", o.spectral ? "spectral" : "rgb"},
                      {"wave_size", o.wave_size}};
  if (merges_vertices(o.integrator)) j["vcm"] = {{"radius", o.vcm_radius}, {"alpha", o.vcm_alpha}};
  if (scales_roulette(o.integrator)) j["roulette"] = o.roulette_scale;
  if (splits_camera_samples(o.integrator) && o.split != 1) j["split"] = split_text(o.split);
  if (o.light_choice != LightChoiceKind::Auto) j["light_choice"] = name(o.light_choice);
  if (uses_light_subpath_rate(o.integrator))
    j["light_subpaths"] = o.light_subpath_rate == kLightSubpathsAuto ? nlohmann::json("auto") : nlohmann::json(o.light_subpath_rate);
  if (o.guiding) j["guiding"] = true;
  if (o.guide_light_subpaths) j["guide_light"] = true;
  if (o.any_guiding()) j["guide_distribution"] = name(o.guide_distribution);
  if (o.any_guiding() && !o.guide_stop) j["guide_stop"] = "never";
  return j;
}

void add_render_settings(ImageMetadata& md, const RenderOptions& o) {
  md.emplace_back("lantern:budget", budget(o));
  md.emplace_back("lantern:sampler", sampler(o));
  md.emplace_back("lantern:light_sampler", name(o.light_sampler));
  if (o.light_choice != LightChoiceKind::Auto) md.emplace_back("lantern:light_choice", name(o.light_choice));
  md.emplace_back("lantern:mis", name(o.mis));
  md.emplace_back("lantern:wave_size", std::to_string(o.wave_size));
  if (scales_roulette(o.integrator)) md.emplace_back("lantern:roulette", exact_text(o.roulette_scale));
  if (splits_camera_samples(o.integrator) && o.split != 1) md.emplace_back("lantern:split", split_text(o.split));
  if (uses_light_subpath_rate(o.integrator)) md.emplace_back("lantern:light_subpaths", light_subpaths_text(o.light_subpath_rate));
  if (o.guiding) md.emplace_back("lantern:guiding", "on");
  if (o.guide_light_subpaths) md.emplace_back("lantern:guide-light", "on");
  if (o.any_guiding()) md.emplace_back("lantern:guide-distribution", name(o.guide_distribution));
  if (o.any_guiding() && !o.guide_stop) md.emplace_back("lantern:guide-stop", "never");
}

}  // namespace lantern
