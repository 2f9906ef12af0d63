// A conformance scene's data file (tests/conformance/*.json): the scene,
// its regions, pbrt-v4's region means and standard errors, the command and
// version that measured them, how Lantern renders it, and the tolerance.
#pragma once

#include <fstream>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>
#include <vector>

#include "conformance/region_stats.h"

namespace lantern::conformance {

struct Region {
  std::string name;
  Box box;
  RegionStats reference;  // pbrt-v4's
  // >= 0: this region's own tolerances (its "why" says what differs); with
  // rgb_only, only for the RGB renderer (what it models differently from
  // pbrt-v4's sampled wavelengths), the spectral one held to the file's
  double relative = -1.0, absolute = -1.0;
  bool rgb_only = false;
};

struct ReferenceData {
  std::string path;   // of the data file
  std::string scene;  // relative to the data file
  std::vector<std::string> integrators{"path"};
  std::vector<std::string> modes{"rgb", "spectral"};  // Lantern's colour: RGB, sampled wavelengths
  int spp = 0;  // Lantern's; 0: the scene's
  // Allowed: z standard errors of the difference, plus `relative` of
  // pbrt-v4's mean for what the two model differently (`why` says what).
  double z = 4.5, relative = 0.005, absolute = 1e-4;
  std::string why;
  bool rgb_only = false;  // the tolerance is RGB's against spectral: the spectral renderer keeps the defaults
  nlohmann::json json;  // the whole file, kept so the measuring tool rewrites it whole
  std::vector<Region> regions;
};

// With `measured`, every region must carry pbrt-v4's figures (the test);
// the measuring tool reads files that do not have them yet.
inline ReferenceData read_reference_data(const std::string& path, bool measured = true) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error(path + ": cannot open");
  ReferenceData d;
  d.path = path;
  try {
    d.json = nlohmann::json::parse(in);
    d.scene = d.json.at("scene").get<std::string>();
    const auto& l = d.json.value("lantern", nlohmann::json::object());
    if (l.contains("integrators")) d.integrators = l["integrators"].get<std::vector<std::string>>();
    d.spp = l.value("spp", 0);
    if (l.contains("modes")) d.modes = l["modes"].get<std::vector<std::string>>();
    const auto& t = d.json.value("tolerance", nlohmann::json::object());
    d.z = t.value("z", d.z);
    d.relative = t.value("relative", d.relative);
    d.absolute = t.value("absolute", d.absolute);
    d.why = t.value("why", std::string());
    d.rgb_only = t.value("rgb_only", false);
    for (const auto& r : d.json.at("regions")) {
      Region g;
      g.name = r.at("name").get<std::string>();
      const auto b = r.at("box").get<std::vector<int>>();
      if (b.size() != 4) throw std::runtime_error("region " + g.name + ": box is [x0 y0 x1 y1]");
      g.box = Box{b[0], b[1], b[2], b[3]};
      if (r.contains("tolerance")) {
        g.relative = r["tolerance"].value("relative", -1.0);
        g.absolute = r["tolerance"].value("absolute", -1.0);
        g.rgb_only = r["tolerance"].value("rgb_only", false);
        if (r["tolerance"].value("why", std::string()).empty())
          throw std::runtime_error("region " + g.name + ": a tolerance of its own needs a \"why\"");
      }
      if (measured && !r.contains("pbrt"))
        throw std::runtime_error("region " + g.name + " has no pbrt-v4 figures: measure the scene (README.md)");
      if (r.contains("pbrt")) {
        const auto m = r["pbrt"].at("mean").get<std::vector<double>>();
        const auto e = r["pbrt"].at("stderr").get<std::vector<double>>();
        for (int c = 0; c < 3; ++c) g.reference.mean[c] = m.at(size_t(c)), g.reference.stderr_[c] = e.at(size_t(c));
      }
      d.regions.push_back(g);
    }
  } catch (const nlohmann::json::exception& e) {
    throw std::runtime_error(path + ": " + e.what());
  }
  return d;
}

}  // namespace lantern::conformance
