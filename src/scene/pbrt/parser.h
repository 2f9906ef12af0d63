// Reads pbrt-v4 scene text (with pbrt-v3 names of common materials) and
// drives a SceneBuilder.
#pragma once

#include <string>

#include "scene/builder.h"

namespace lantern::pbrt {

// base_dir: where relative file names (Include, plymesh, textures) resolve.
void parse_file(const std::string& path, SceneBuilder& builder);
void parse_string(const std::string& text, const std::string& name, const std::string& base_dir, SceneBuilder& builder);

}  // namespace lantern::pbrt
