// lantern-make-nvdb OUT.nvdb [--burning]: writes the two-blob NanoVDB
// density grid of perf/media/nvdb_blobs.h (for pbrt-v4 to render the same
// scene); with --burning, a temperature grid beside it, as
// perf/media/nanovdb-burning.pbrt reads.
#include <cstdio>
#include <exception>
#include <string>

#include "nvdb_blobs.h"

int main(int argc, char** argv) {
  const bool burning = argc == 3 && std::string(argv[2]) == "--burning";
  if (argc != 2 && !burning) {
    std::fprintf(stderr, "usage: lantern-make-nvdb OUT.nvdb [--burning]\n");
    return 2;
  }
  try {
    if (burning) lantern::nvdb_blobs::write_burning(argv[1]);
    else lantern::nvdb_blobs::write(argv[1]);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "lantern-make-nvdb: %s\n", e.what());
    return 1;
  }
  return 0;
}
