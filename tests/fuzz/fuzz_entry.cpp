#include "fuzz_entry.h"

#include <string>

#include "lantern/error.h"
#include "scene/builder.h"
#include "scene/pbrt/parser.h"
#include "scene/ply.h"

namespace lantern::fuzz {

// Relative names in fuzzed text (Include, plymesh, imagemap) resolve inside
// a folder that does not exist, so a fuzz run never reads the project's
// files; they are reported as "cannot open", which is itself a path worth
// exercising.
constexpr const char* kNowhere = "/nonexistent-lantern-fuzz-dir";

void load_pbrt(const uint8_t* data, size_t size) {
  std::string text(reinterpret_cast<const char*>(data), size);
  Scene scene;
  SceneBuilder builder(scene, nullptr);
  try {
    pbrt::parse_string(text, "fuzz.pbrt", kNowhere, builder);
    builder.finish();
  } catch (const InputError&) {
  }
}

void load_ply(const uint8_t* data, size_t size) {
  std::string bytes(reinterpret_cast<const char*>(data), size);
  try {
    parse_ply(bytes, "fuzz.ply");
  } catch (const InputError&) {
  }
}

}  // namespace lantern::fuzz
