// Reads pbrt-v4 scene text (with pbrt-v3 names of common materials) and
// drives a ParserTarget (a SceneBuilder, to make a Scene).
#pragma once

#include <string>

#include "scene/pbrt/parser_target.h"

namespace lantern::pbrt {

// base_dir: where relative file names (Include, plymesh, textures) resolve.
void parse_file(const std::string& path, ParserTarget& target);
void parse_string(const std::string& text, const std::string& name, const std::string& base_dir, ParserTarget& target);

}  // namespace lantern::pbrt
