// A command-line render with its watchers: a display server that shows the
// image as it refines (app/display_server.h) and partial images written to
// the output as passes end (--write-partial-images, as pbrt-v4's flag).
// Neither slows the render beyond the snapshots they take, and neither
// fails it: a server that cannot be reached, or an image that cannot be
// written, is a warning.
#pragma once

#include <functional>
#include <string>

#include "lantern/image.h"
#include "lantern/render.h"

namespace lantern {

struct Watchers {
  std::string display_server;  // HOST:PORT, or "": none
  std::string display_name;    // the image's name there
  std::string partial_path;    // where partial images go, or "": none
  double partial_seconds = 10.0;  // at most one every this many seconds, at the end of a pass
  // The header of a partial image (its samples, spp and time so far in
  // the result's stats).
  std::function<ImageMetadata(const RenderResult& partial)> partial_metadata;
  bool log_passes = false;  // at --log-level verbose, a line per pass (the process that reports)
};

RenderResult render_watched(const Scene& scene, const RenderOptions& options, RenderHooks hooks,
                            const Watchers& watchers);

}  // namespace lantern
