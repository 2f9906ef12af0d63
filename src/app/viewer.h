// `lantern view`: a window that shows a render as it refines (GLFW and
// OpenGL), driving the same RenderSession as `lantern render`
// (docs/viewer.md has the keys).
#pragma once

#include <string>

#include "app/provenance.h"
#include "app/render_request.h"

namespace lantern {

struct ViewArgs {
  RenderRequest req;
  std::string scene;
  std::string screenshot;  // file name prefix of F1's screenshots ("": the scene's output name + "-view")
  std::string texture_dir;
  double texture_cache_mb = 1024.0;
  bool lenient = false;
  float exposure = 1.f;
};

// Runs until the window is closed (0), or returns 1 when no window can be
// opened (no display). Throws what loading the scene throws.
int run_view(const ViewArgs& args, const Provenance& provenance);

}  // namespace lantern
