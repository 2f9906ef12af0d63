// lantern-bench: the benchmark drivers of perf/ (see perf/README.md).
#include <CLI/CLI.hpp>
#include <iostream>

#include "bench.h"

int main(int argc, char** argv) {
  CLI::App app{"Lantern's benchmark drivers: throughput, ray back ends, scaling, convergence"};
  app.require_subcommand(1);
  bench::Common c;
  app.add_option("--scenes-dir", c.scenes_dir, "Folder of the shipped scenes");
  app.add_option("--out", c.out_dir, "Also write each table as CSV into this folder");
  app.add_option("--threads", c.threads, "Threads (default: all)");

  std::vector<std::string> scenes = {"cornell-box", "cornell-box-tiny-light", "lantern", "door-ajar", "caustics"};
  int spp = 16, width = 240, rounds = 3;
  auto* tp = app.add_subcommand("throughput", "Samples/s, rays/s by kind and stage shares per scene and integrator");
  tp->add_option("--scenes", scenes, "Scene names")->delimiter(',');
  tp->add_option("--spp", spp, "Samples per pixel");
  tp->add_option("--resolution", width, "Width (height = 3/4 of it)");

  std::string scene = "cornell-box", integrator = "path";
  int bspp = 32;
  auto* be = app.add_subcommand("backends", "Ray back ends on the same scene and integrator");
  be->add_option("--scene", scene);
  be->add_option("--integrator", integrator);
  be->add_option("--spp", bspp);
  be->add_option("--rounds", rounds);

  std::string sscene = "cornell-box", sintegrator = "path";
  int sspp = 16;
  auto* sc = app.add_subcommand("scaling", "Samples/s against threads and wave size");
  sc->add_option("--scene", sscene);
  sc->add_option("--integrator", sintegrator);
  sc->add_option("--spp", sspp);

  std::string cscene = "lantern", reference;
  double max_seconds = 16.0;
  std::vector<std::string> cintegrators = {"path", "lt", "bdpt"};
  auto* cv = app.add_subcommand("convergence", "relMSE against time for path, lt and bdpt (or --integrators)");
  cv->add_option("--scene", cscene);
  cv->add_option("--integrators", cintegrators, "Integrators to run, comma-separated (default path,lt,bdpt)")
      ->delimiter(',')
      ->check(CLI::IsMember({"path", "bdpt", "lt", "vcm", "bpm", "ppm"}));
  cv->add_option("--reference", reference, "Reference image (default: perf/references/<scene>.exr)");
  cv->add_option("--max-seconds", max_seconds, "Largest budget; budgets halve down to 1/32 of it");

  CLI11_PARSE(app, argc, argv);
  try {
    if (tp->parsed()) return bench::throughput(c, scenes, spp, width, width * 3 / 4);
    if (be->parsed()) return bench::backends(c, scene, integrator, bspp, rounds);
    if (sc->parsed()) return bench::scaling(c, sscene, sintegrator, sspp);
    if (reference.empty()) reference = "perf/references/" + cscene + ".exr";
    return bench::convergence(c, cscene, reference, max_seconds, cintegrators);
  } catch (const std::exception& e) {
    std::cerr << "error: " << e.what() << "\n";
    return 1;
  }
}
