#include "fuzz_entry.h"

#include <unistd.h>

#include <cstdio>
#include <fstream>
#include <string>

#include "lantern/error.h"
#include "light/light_sampler.h"
#include "medium/nanovdb_grid.h"
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
    pbrt::parse_string(text, "fuzz.pbrt", kNowhere, builder, 1);
    builder.finish();
    // What every render builds first from the scene: the light BVH (a
    // light's vertex at 3e38 once overflowed its build's buckets).
    LightSampler bvh(scene.lights, scene.shapes, scene.textures, LightSamplerKind::Bvh);
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

// The reader takes a file: the bytes go to one of this process's own.
void load_nvdb(const uint8_t* data, size_t size) {
  static const std::string path = "/tmp/lantern-fuzz-" + std::to_string(getpid()) + ".nvdb";
  std::ofstream(path, std::ios::binary | std::ios::trunc).write(reinterpret_cast<const char*>(data), std::streamsize(size));
  try {
    const VdbGrid g = VdbGrid::load(path, "density", Mat4(1.f));
    float t;
    for (int k = 0; k < 3; ++k) {
      const Vec3 o(-50.f + 7.f * k, -40.f, -30.f), d = glm::normalize(Vec3(1.f, 0.8f + 0.1f * k, 0.6f));
      g.integrate(o, d, 0.f, 200.f, -1.f, &t);
      g.integrate(o, d, 0.f, 200.f, 0.5f, &t);
      g.density(o + d * 50.f);
    }
  } catch (const std::runtime_error&) {  // InputError or the reader's own message
  }
  std::remove(path.c_str());
}

}  // namespace lantern::fuzz
