// `lantern render SCENE`: load, render, and write the image and whatever
// else was asked for (statistics, a timeline, per-strategy images, a part
// file, partial images, a display server's stream).
#pragma once

#include <cstdint>
#include <string>

#include <CLI/CLI.hpp>

#include "app/provenance.h"
#include "app/render_request.h"

namespace lantern {

class MpiSession;  // src/distributed/mpi_render.h

struct RenderArgs {
  RenderRequest req;  // what the render options ask of the scene
  std::string scene, output, strategies, stats, dump_rays, checkpoint_file;
  std::string texture_dir, trace, part, display_server;
  std::string log_level = "info", log_file;
  uint64_t trace_waves = 1000;
  double checkpoint = 0.0, texture_cache_mb = 1024.0, progress_interval = 10.0;
  // --write-partial-images[=SECONDS]: seconds between them ("": none); a
  // string, as CLI11 reads a flag's value as an integer.
  std::string partial_images;
  bool resume = false, keep_checkpoint = false;
  bool quiet = false;
  bool lenient = false;  // unknown scene parameters are warnings
  std::string memory_layout = "auto";
};

// The render subcommand's options (the request's, app/command_line.h, and
// the files and reports of a command-line render).
void add_render_command_options(CLI::App& render, RenderArgs& args);

// This process among the MPI ranks of one render (rank 0 of 1 without
// mpirun); rank 0 writes the image and reports.
struct Ranks {
  int rank = 0, count = 1;
  MpiSession* mpi = nullptr;
};

// Exit status as docs/cli.md tables it (0, 1, 130); InputErrors and
// cli::UsageErrors propagate (exit 2 in main).
int run_render(const RenderArgs& args, const Provenance& provenance, const Ranks& ranks);

}  // namespace lantern
