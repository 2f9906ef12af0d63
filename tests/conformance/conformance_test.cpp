// The conformance suite: each scene in tests/conformance/ rendered by
// Lantern, its regions compared with pbrt-v4's (measured offline and kept in
// the scene's data file, tests/conformance/README.md). A region fails where
// a channel differs by more than z standard errors of the difference plus
// the file's stated relative tolerance.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>

#include "conformance/reference_data.h"
#include "lantern/render.h"
#include "lantern/scene.h"

namespace lantern::conformance {
namespace {

namespace fs = std::filesystem;

std::vector<std::string> data_files() {
  std::vector<std::string> files;
  for (const auto& e : fs::directory_iterator(LANTERN_CONFORMANCE_DIR))
    if (e.path().extension() == ".json") files.push_back(e.path().string());
  std::sort(files.begin(), files.end());
  return files;
}

class Conformance : public ::testing::TestWithParam<std::string> {};

Image render_with_lantern(const ReferenceData& d, const std::string& integrator, bool spectral, uint64_t seed) {
  const std::string scene_path = (fs::path(d.path).parent_path() / d.scene).string();
  auto scene = load_scene(scene_path);
  const SceneSettings& ss = scene_settings(*scene);
  RenderOptions o;
  o.integrator = parse_integrator(integrator);
  o.spp = d.spp > 0 ? d.spp : ss.spp;
  // The sanitizer suite scales samples down (LANTERN_TEST_SPP_SCALE, as
  // render_runs does): a region's standard error, measured from the two
  // renders, widens with it, so the tolerance stays exact.
  if (const char* scale = std::getenv("LANTERN_TEST_SPP_SCALE"))
    o.spp = std::max(4, int(std::lround(o.spp * std::atof(scale))));
  o.maxdepth = ss.maxdepth;
  o.sampler = ss.sampler;
  o.light_sampler = ss.light_sampler;
  o.wave_size = merges_vertices(parse_integrator(integrator)) ? 16384 : 4096;
  o.seed = seed;
  o.spectral = spectral;
  return render(*scene, o).image;
}

TEST_P(Conformance, RegionsMatchPbrtV4) {
  const ReferenceData d = read_reference_data(GetParam());
  ASSERT_FALSE(d.regions.empty()) << d.path;
  const ReferenceData defaults;  // the suite's tolerance
  for (const std::string& mode : d.modes)
    for (const std::string& integrator : d.integrators) {
      const bool spectral = mode == "spectral";
      // With sampled wavelengths in the file's first integrator only: the
      // others' agreement with it is held in tests/spectral_test.cpp.
      if (spectral && integrator != d.integrators.front()) continue;
      const Image a = render_with_lantern(d, integrator, spectral, 1),
                  b = render_with_lantern(d, integrator, spectral, 2);
      int failed = 0;
      for (const Region& r : d.regions) {
        const RegionStats l = region_stats(a, b, r.box);
        const bool own = !(spectral && r.rgb_only);  // the region's own tolerance applies
        for (int c = 0; c < 3; ++c) {
          const double p = r.reference.mean[c];
          const double se = std::hypot(l.stderr_[c], r.reference.stderr_[c]);
          const bool file_own = !(spectral && d.rgb_only);
          const double relative = own && r.relative >= 0.0 ? r.relative : file_own ? d.relative : defaults.relative;
          const double absolute = own && r.absolute >= 0.0 ? r.absolute : file_own ? d.absolute : defaults.absolute;
          const double allowed = d.z * se + relative * std::fabs(p) + absolute;
          const double diff = l.mean[c] - p;
          if (std::fabs(diff) > allowed) ++failed;
          EXPECT_LE(std::fabs(diff), allowed)
              << d.scene << " (" << integrator << ", " << mode << "), region " << r.name << ", channel "
              << "RGB"[c] << ": Lantern " << l.mean[c] << " +- " << l.stderr_[c] << ", pbrt-v4 " << p << " +- "
              << r.reference.stderr_[c] << " (ratio " << l.mean[c] / p << ")";
        }
      }
      if (failed)
        std::printf("%s (%s, %s): %d of %zu region channels differ\n", d.scene.c_str(), integrator.c_str(),
                    mode.c_str(), failed, 3 * d.regions.size());
    }
}

std::string test_name(const ::testing::TestParamInfo<std::string>& info) {
  std::string n = fs::path(info.param).stem().string();
  for (char& c : n)
    if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
  return n;
}

INSTANTIATE_TEST_SUITE_P(PbrtV4, Conformance, ::testing::ValuesIn(data_files()), test_name);

}  // namespace
}  // namespace lantern::conformance
