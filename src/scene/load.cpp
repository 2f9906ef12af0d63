// The public entry points for loading a scene.
#include <filesystem>

#include "scene/builder.h"
#include "scene/pbrt/parser.h"

namespace lantern {

std::shared_ptr<Scene> load_scene(const std::string& path, const LoadOptions& options) {
  auto scene = std::make_shared<Scene>();
  SceneBuilder b(*scene, options.warn);
  pbrt::parse_file(path, b);
  b.finish();
  return scene;
}

std::shared_ptr<Scene> load_scene_from_string(const std::string& text, const std::string& name, const LoadOptions& options) {
  auto scene = std::make_shared<Scene>();
  SceneBuilder b(*scene, options.warn);
  pbrt::parse_string(text, name, std::filesystem::current_path().string(), b);
  b.finish();
  return scene;
}

const SceneSettings& scene_settings(const Scene& scene) { return scene.settings; }

}  // namespace lantern
