// lantern-conformance-measure DATA.json SEED1.exr SEED2.exr --renderer TEXT --command TEXT
//
// Fills a conformance data file with the region means and standard errors
// of two renders of its scene by pbrt-v4 with different seeds, and records
// the renderer's version and the command that made the images
// (tests/conformance/README.md).
#include <cstdio>
#include <fstream>
#include <string>

#include "conformance/reference_data.h"
#include "lantern/image.h"

int main(int argc, char** argv) {
  using namespace lantern::conformance;
  std::string data_path, image_a, image_b, renderer, command;
  for (int i = 1; i < argc; ++i) {
    std::string a = argv[i];
    if (a == "--renderer" && i + 1 < argc) renderer = argv[++i];
    else if (a == "--command" && i + 1 < argc) command = argv[++i];
    else if (data_path.empty()) data_path = a;
    else if (image_a.empty()) image_a = a;
    else if (image_b.empty()) image_b = a;
    else {
      std::fprintf(stderr, "unexpected argument %s\n", a.c_str());
      return 2;
    }
  }
  if (data_path.empty() || image_b.empty() || renderer.empty() || command.empty()) {
    std::fprintf(stderr, "usage: lantern-conformance-measure DATA.json SEED1.exr SEED2.exr --renderer TEXT --command TEXT\n");
    return 2;
  }
  try {
    ReferenceData d = read_reference_data(data_path, false);
    const lantern::Image a = lantern::read_image(image_a), b = lantern::read_image(image_b);
    d.json["reference"] = {{"renderer", renderer}, {"command", command}};
    for (auto& r : d.json["regions"]) {
      const auto box = r.at("box").get<std::vector<int>>();
      const RegionStats s = region_stats(a, b, Box{box.at(0), box.at(1), box.at(2), box.at(3)});
      r["pbrt"] = {{"mean", {s.mean[0], s.mean[1], s.mean[2]}}, {"stderr", {s.stderr_[0], s.stderr_[1], s.stderr_[2]}}};
      std::printf("%-24s %.5f %.5f %.5f  (+- %.5f %.5f %.5f)\n", r["name"].get<std::string>().c_str(), s.mean[0],
                  s.mean[1], s.mean[2], s.stderr_[0], s.stderr_[1], s.stderr_[2]);
    }
    std::ofstream out(data_path);
    out << d.json.dump(2) << "\n";
    if (!out) throw std::runtime_error(data_path + ": cannot write");
  } catch (const std::exception& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 1;
  }
  return 0;
}
