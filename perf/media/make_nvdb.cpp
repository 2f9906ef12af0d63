// lantern-make-nvdb OUT.nvdb: writes the two-blob NanoVDB density grid of
// perf/media/nvdb_blobs.h (for pbrt-v4 to render the same scene).
#include <cstdio>
#include <exception>

#include "nvdb_blobs.h"

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: lantern-make-nvdb OUT.nvdb\n");
    return 2;
  }
  try {
    lantern::nvdb_blobs::write(argv[1]);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "lantern-make-nvdb: %s\n", e.what());
    return 1;
  }
  return 0;
}
