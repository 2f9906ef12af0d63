// Where an image or a measurement came from, so that a figure can be
// reproduced from its own files: the program (version, commit, build type,
// compiler), the machine (CPU model and count), when, and the command.
// Written into the image header (lantern:* keys), the --stats JSON, and
// printed by `lantern --version`.
#pragma once

#include <nlohmann/json.hpp>

#include <string>

#include "lantern/image.h"
#include "lantern/render.h"

namespace lantern {

struct BuildInfo {
  const char* version;
  const char* commit;  // "unknown" outside a git checkout; "-modified" with local changes
  const char* build_type;
  const char* compiler;
};
extern const BuildInfo kBuildInfo;  // written at build time (src/app/build_info.cmake)

struct Provenance {
  std::string cpu;       // the model name /proc/cpuinfo gives ("unknown" without it)
  unsigned cores = 0;    // hardware threads
  std::string date;      // UTC, ISO 8601
  std::string command;   // the command line, arguments quoted where they need it
};
Provenance provenance(int argc, char** argv);

// "lantern 0.1.0 (commit 1a2b3c4d5e6f, Release, GNU 12.2.0)"
std::string version_line();

nlohmann::json provenance_json(const Provenance& p);
void add_provenance(ImageMetadata& md, const Provenance& p);

// Every setting of a render that changes its image or its figures:
// integrator, maxdepth, seed, budget, sampler, light sampler, MIS, colour,
// wave size.
nlohmann::json render_settings_json(const RenderOptions& o);
void add_render_settings(ImageMetadata& md, const RenderOptions& o);

}  // namespace lantern
