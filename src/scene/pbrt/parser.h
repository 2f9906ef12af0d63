// Reads pbrt-v4 scene text (with pbrt-v3 names of common materials) and
// drives a ParserTarget (a SceneBuilder, to make a Scene).
#pragma once

#include <string>

#include "scene/pbrt/parser_target.h"

namespace lantern::pbrt {

// base_dir: where relative file names (Include, plymesh, textures) resolve.
// threads: how many threads parse Import'ed files (0: as many as oneTBB
// may use; 1: each in place). The target sees the same calls in the same
// order whatever the count (docs/scene-format.md, "Import").
void parse_file(const std::string& path, ParserTarget& target, unsigned threads = 0);
void parse_string(const std::string& text, const std::string& name, const std::string& base_dir, ParserTarget& target,
                  unsigned threads = 0);

}  // namespace lantern::pbrt
