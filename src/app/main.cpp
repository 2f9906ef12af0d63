// The lantern command line.
#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>
#include <unistd.h>

#include <cmath>
#include <csignal>
#include <cstdio>
#include <iostream>
#include <sstream>

#include "app/cli_checks.h"
#include "app/command_line.h"
#include "app/huge_pages.h"
#include "app/log.h"
#include "app/merge_command.h"
#include "app/outputs.h"
#include "app/provenance.h"
#include "app/render_command.h"
#include "app/stats_report.h"
#include "app/viewer.h"
#include "film/checkpoint.h"
#include "film/image_metrics.h"
#include "lantern/scene.h"
#ifdef LANTERN_HAVE_MPI
#include "distributed/mpi_render.h"
#endif

namespace {

// This process's place among MPI ranks (rank 0 of 1 without mpirun).
lantern::Ranks g_ranks;

struct CompareArgs {
  std::string a, ref, error_image;
  double error_scale = 1.0;
  bool json = false;
};

// Prints the metrics as "name value" lines, easy to read and to parse, or
// as one JSON object (--json; an infinite PSNR, of identical images, is null).
// With the error map on standard output (--error-image -), the metrics go
// to standard error.
int run_compare(const CompareArgs& c) {
  lantern::Image a = lantern::read_image(c.a), ref = lantern::read_image(c.ref);
  const lantern::ImageComparison m = lantern::compare_images(a, ref);
  std::FILE* text = c.error_image == "-" ? stderr : stdout;
  if (c.json) {
    nlohmann::json j = {{"image", c.a}, {"reference", c.ref}, {"width", a.width}, {"height", a.height}};
    j.update(lantern::comparison_json(m));
    std::fprintf(text, "%s\n", j.dump(2).c_str());
  } else {
    // (The first seven lines as they have always been; the others after.)
    std::fprintf(text, "mse %.9g\nrelmse %.9g\nmae %.9g\n", m.mse, m.relmse, m.mae);
    std::fprintf(text, "mean %.9g %.9g %.9g\nmean_ref %.9g %.9g %.9g\nratio %.9g %.9g %.9g\nnonfinite_pixels %zu\n",
                m.mean_a[0], m.mean_a[1], m.mean_a[2], m.mean_ref[0], m.mean_ref[1], m.mean_ref[2], m.ratio[0],
                m.ratio[1], m.ratio[2], m.nonfinite);
    std::fprintf(text, "psnr %.9g\nrelmse_robust %.9g\nrobust_excluded_pixels %zu\n", m.psnr, m.relmse_robust,
                m.robust_excluded);
    std::fprintf(text, "pbrt_mse %.9g %.9g %.9g\npbrt_mrse %.9g %.9g %.9g\n", m.pbrt_mse[0], m.pbrt_mse[1], m.pbrt_mse[2],
                m.pbrt_mrse[0], m.pbrt_mrse[1], m.pbrt_mrse[2]);
  }
  if (!c.error_image.empty())
    lantern::write_output_image(c.error_image, lantern::relative_error_image(a, ref, c.error_scale, true),
                         {{"lantern:error_map", "relative squared error per pixel, blue 0 to red " +
                                                    std::to_string(c.error_scale) +
                                                    " and above; the bar below: the scale, 0 to " +
                                                    std::to_string(c.error_scale)}});
  return 0;
}

// "name value" lines: the size and the render settings an image was made
// with; for a checkpoint or a part file, the settings of the render it
// belongs to (its fingerprint), the units it holds and its samples.
int run_info(const std::string& path) {
  std::string fingerprint;
  try {
    fingerprint = lantern::read_checkpoint_fingerprint(path);
  } catch (const lantern::InputError&) {  // not one: an image
    lantern::Image img = lantern::read_image(path);
    std::printf("resolution %d %d\n", img.width, img.height);
    for (const auto& [k, v] : lantern::read_image_metadata(path)) std::printf("%s %s\n", k.c_str(), v.c_str());
    return 0;
  }
  lantern::Film film(0, 0, lantern::PixelFilter{});
  const lantern::CheckpointInfo ci = lantern::read_film_file(path, film);
  std::istringstream lines(fingerprint);
  for (std::string line; std::getline(lines, line);)
    if (const size_t eq = line.find('='); eq != std::string::npos)
      std::printf("%s %s\n", line.substr(0, eq).c_str(), line.substr(eq + 1).c_str());
  std::printf("part %u/%u\nunits_done %llu\nunits_total %llu\nsamples %llu\nrender_seconds %.3f\n",
              ci.share.index + 1, ci.share.count, (unsigned long long)ci.done.size(),
              (unsigned long long)(uint64_t(ci.passes) * ci.waves), (unsigned long long)film.total_samples(),
              ci.elapsed_seconds);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  // First, before any thread or MPI: the heap in huge pages (app/huge_pages.h).
  lantern::restart_with_huge_pages(argv);
#ifdef LANTERN_HAVE_MPI
  // Under mpirun: MPI for the whole run. A rank that fails ends them all
  // (MPI_Abort) rather than leaving the others waiting for it.
  std::unique_ptr<lantern::MpiSession> mpi;
  if (lantern::MpiSession::launched()) {
    mpi = std::make_unique<lantern::MpiSession>(argc, argv);
    g_ranks.mpi = mpi.get();
    g_ranks.rank = mpi->rank();
    g_ranks.count = mpi->size();
  }
  auto fail = [&](int code) {
    if (g_ranks.count > 1) {
      std::cerr << "rank " << g_ranks.rank << " of " << g_ranks.count << " failed; ending all ranks\n";
      mpi->abort_all(code);
    }
    return code;
  };
#else
  auto fail = [](int code) { return code; };
#endif
  // A reader that goes away (a closed pipe) is an error to report, not a
  // signal that ends the process with the image unwritten.
  std::signal(SIGPIPE, SIG_IGN);
  const lantern::Provenance provenance = lantern::provenance(argc, argv);
  CLI::App app{"Lantern: physically based rendering with bidirectional path tracing"};
  app.require_subcommand(1);
  lantern::RenderArgs a;
  CLI::App* render = app.add_subcommand("render", "Render a pbrt-v4 scene to an image");
  lantern::add_render_command_options(*render, a);
  CompareArgs ca;
  CLI::App* compare = app.add_subcommand("compare", "Error metrics of an image against a reference");
  compare->add_option("image", ca.a, "Image to measure")->required()->check(CLI::ExistingFile);
  compare->add_option("reference", ca.ref, "Reference image")->required()->check(CLI::ExistingFile);
  compare->add_option("--error-image", ca.error_image,
                      "Write a false-colour map of the relative squared error, with its scale as a bar below");
  compare->add_flag("--json", ca.json, "Print the metrics as one JSON object");
  compare->add_option("--error-scale", ca.error_scale, "Relative squared error shown as full red")
      ->check(lantern::cli::number_in(0.0, HUGE_VAL, false, "a positive number"));
  lantern::MergeArgs ma;
  CLI::App* merge = app.add_subcommand("merge", "Add the part files of a render (render --part K/N) into its image");
  merge->add_option("parts", ma.parts, "Part files, in any order")->required();
  merge->add_option("-o,--output", ma.output, "Output image (.exr, .png)")->required();
  merge->add_flag("--preview", ma.preview,
                  "Merge an incomplete set (missing or unfinished parts): each pixel normalised by its own samples");
  merge->add_flag("-q,--quiet", ma.quiet, "No summary");
  lantern::ViewArgs va;
  CLI::App* view = app.add_subcommand("view", "Show a render refining in a window; keys move the camera, F1 saves, R reloads (docs/viewer.md)");
  view->add_option("scene", va.scene, "Scene file (pbrt-v4 format)")->required();
  lantern::cli::add_render_request_options(*view, va.req);
  view->add_option("--screenshot", va.screenshot,
                   "F1 writes PREFIX-N.exr and PREFIX-N.png (default: the scene's output name + \"-view\")");
  view->add_option("--exposure", va.exposure, "Display exposure (a factor; + and - double and halve it)")
      ->check(lantern::cli::number_in(0.0, HUGE_VAL, false, "a positive number"));
  view->add_option("--texture-cache", va.texture_cache_mb, "Memory for image texture tiles, in MB (default: 1024)")
      ->check(lantern::cli::number_in(1.0, 1048576.0, true, "a number of megabytes from 1 to 1048576"));
  view->add_option("--texture-dir", va.texture_dir, "Where images are prepared as tiled, MIP-mapped textures");
  view->add_flag("--lenient", va.lenient, "A scene parameter neither pbrt-v4 nor pbrt-v3 reads is a warning, not an error");
  std::string info_image;
  CLI::App* info = app.add_subcommand("info", "Print an image's size and the settings it was rendered with, or those "
                                              "of a checkpoint or part file and the work it holds");
  info->add_option("image", info_image, "Image, checkpoint or part file written by lantern render")
      ->required()
      ->check(CLI::ExistingFile);
  app.set_version_flag("--version", lantern::version_line());
  if (const int code = lantern::cli::parse_command_line(app, argc, argv); code >= 0) return code == 0 ? 0 : fail(code);
  try {
    if (compare->parsed()) return run_compare(ca);
    if (info->parsed()) return run_info(info_image);
    if (merge->parsed()) return lantern::run_merge(ma, provenance);
    if (view->parsed()) {
#ifdef LANTERN_HAVE_VIEWER
      return lantern::run_view(va, provenance);
#else
      std::cerr << "error: this build has no viewer: GLFW was not found when it was configured (install "
                   "libglfw3-dev, or run scripts/install-deps.sh, and configure again)\n";
      return 1;
#endif
    }
    return lantern::run_render(a, provenance, g_ranks);
  } catch (const lantern::InputError& e) {
    // Through the log: after a progress line, and into --log-file too.
    lantern::logging::line(lantern::logging::Level::Error, e.what());
    return fail(2);
  } catch (const lantern::cli::UsageError& e) {
    lantern::logging::error("error: %s", e.what());
    return fail(2);
  } catch (const std::bad_alloc&) {
    // What the renderer did not estimate ahead (the film and its buffers
    // are: integrator/render_settings.h) ran out: say how much was in use.
    lantern::logging::error("error: out of memory, with %.1f GiB in use at the peak of %.1f GiB on this machine: render "
                            "a smaller scene or image, a part of it (--cropwindow), or with fewer threads",
                            double(lantern::peak_rss_bytes()) / (1 << 30),
                            double(sysconf(_SC_PHYS_PAGES)) * double(sysconf(_SC_PAGE_SIZE)) / (1 << 30));
    return fail(1);
  } catch (const std::exception& e) {
    lantern::logging::error("error: %s", e.what());
    return fail(1);
  }
}
