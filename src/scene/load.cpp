// The public entry points for loading a scene.
#include <filesystem>
#include <optional>

#include <tbb/global_control.h>

#include "scene/builder.h"
#include "scene/pbrt/parser.h"

namespace lantern {

namespace {

std::optional<tbb::global_control> thread_limit(const LoadOptions& options) {
  std::optional<tbb::global_control> limit;
  if (options.threads > 0) limit.emplace(tbb::global_control::max_allowed_parallelism, size_t(options.threads));
  return limit;
}

unsigned parse_threads() {
  return unsigned(tbb::global_control::active_value(tbb::global_control::max_allowed_parallelism));
}

}  // namespace

std::shared_ptr<Scene> load_scene(const std::string& path, const LoadOptions& options) {
  const auto limit = thread_limit(options);
  auto scene = std::make_shared<Scene>();
  SceneBuilder b(*scene, options.warn, options.progress);
  b.set_texture_cache(TextureCacheSettings{options.texture_cache_mb, options.texture_directory});
  b.set_lenient(options.lenient);
  b.set_memory_layout(options.memory_layout);
  b.set_file_progress(options.file_progress);
  if (options.progress) options.progress("parsing " + path);
  pbrt::parse_file(path, b, parse_threads());
  b.finish();
  return scene;
}

std::shared_ptr<Scene> load_scene_from_string(const std::string& text, const std::string& name, const LoadOptions& options) {
  const auto limit = thread_limit(options);
  auto scene = std::make_shared<Scene>();
  SceneBuilder b(*scene, options.warn);
  b.set_texture_cache(TextureCacheSettings{options.texture_cache_mb, options.texture_directory});
  b.set_lenient(options.lenient);
  b.set_memory_layout(options.memory_layout);
  pbrt::parse_string(text, name,
                     options.base_directory.empty() ? std::filesystem::current_path().string()
                                                    : std::filesystem::absolute(options.base_directory).string(),
                     b, parse_threads());
  b.finish();
  return scene;
}

const SceneSettings& scene_settings(const Scene& scene) { return scene.settings; }

SceneInfo scene_info(const Scene& scene) {
  SceneInfo info;
  info.triangles = scene.triangle_count;
  info.spheres = scene.shapes.spheres.size();
  info.lights = scene.lights.all.size();
  info.instances = scene.shapes.instances.size();
  for (const BilinearPatchSet& p : scene.shapes.patches) {
    info.bilinear_patches += p.patches.size();
    info.geometry_bytes += p.positions.capacity() * sizeof(Vec3) + p.normals.capacity() * sizeof(Vec3) +
                           p.uvs.capacity() * sizeof(Vec2) + p.patches.capacity() * sizeof(glm::uvec4);
  }
  for (const CurveSet& c : scene.shapes.curves) {
    info.curve_segments += c.segments();
    info.geometry_bytes += c.control.capacity() * sizeof(glm::vec4) + c.normals.capacity() * sizeof(Vec3) +
                           c.u_range.capacity() * sizeof(Vec2);
  }
  info.instanced_triangles = scene.triangle_count - scene.prototype_triangle_count + scene.instanced_triangle_count;
  if (scene.accel) {
    info.bvh_build_seconds = scene.accel->build_seconds();
    info.bvh_bytes = scene.accel->bytes();
    info.bvh_peak_bytes = scene.accel->peak_bytes();
    info.compact_instances = scene.accel->compact_instances();
    info.compact_bvh = scene.accel->compact_bvh();
  }
  info.geometry_bytes += scene.shapes.instances.capacity() * sizeof(Placement) +
                         scene.shapes.geometries.capacity() * sizeof(Geometry);
  for (const TriangleMesh& m : scene.shapes.meshes)
    info.geometry_bytes += m.positions.capacity() * sizeof(Vec3) + m.triangles.capacity() * sizeof(glm::uvec3) + m.quads.capacity() * sizeof(glm::uvec4) +
                           m.normals.capacity() * sizeof(Vec3) + m.uvs.capacity() * sizeof(Vec2);
  return info;
}

}  // namespace lantern
