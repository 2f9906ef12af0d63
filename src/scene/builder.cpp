#include "scene/builder.h"
#include "geometry/loop_subdivision.h"

#include <tbb/parallel_for.h>

#include <cmath>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <glm/gtc/matrix_inverse.hpp>

#include "material/fresnel.h"
#include "scene/ply.h"
#include "geometry/surface.h"

namespace lantern {

using pbrt::ColorUsage;
using pbrt::ParamSet;

void SceneBuilder::warn(const SourceLocation& where, const std::string& what) const {
  if (warn_) warn_((where.file.empty() ? std::string() : where.str() + ": ") + "warning: " + what);
}

std::string resolve_path(const std::string& base_dir, const std::string& file) {
  std::filesystem::path p(file);
  return p.is_absolute() || base_dir.empty() ? file : (std::filesystem::path(base_dir) / p).string();
}

void SceneBuilder::begin_world(const glm::dmat4& render_from_world, double transform_start, double transform_end) {
  render_from_world_ = render_from_world;
  CameraDesc& c = scene_.camera;
  c.world_from_camera = Mat4(render_from_world * world_from_camera_);
  c.file_world_from_render = Mat4(glm::inverse(render_from_world));
  c.shutter.start = float(transform_start);
  c.shutter.end = float(transform_end);
  if (world_from_camera_ != world_from_camera_end_)
    c.motion = std::make_shared<MotionPath>(
        motion_path(render_from_world * world_from_camera_, render_from_world * world_from_camera_end_));
}

bool swaps_handedness(const Mat4& m) { return glm::determinant(glm::mat3(m)) < 0.f; }

// Carries a mesh into the space it is stored in and checks it. It touches
// nothing but the mesh, so PLY meshes are prepared on any thread.
static void prepare_mesh(TriangleMesh& mesh, const Mat4& M, bool reverse_orientation, const ParamSet& ps,
                         const std::string& source) {
  glm::mat3 N = glm::inverseTranspose(glm::mat3(M));
  for (size_t i = 0; i < mesh.positions.size(); ++i) {
    Vec3& p = mesh.positions[i];
    Vec3 before = p;
    p = Vec3(M * Vec4(p, 1.f));
    if (!is_finite(p)) {
      char xyz[96];
      std::snprintf(xyz, sizeof xyz, "(%g, %g, %g)", double(before.x), double(before.y), double(before.z));
      ps.fail("vertex " + std::to_string(i) + (source.empty() ? "" : " of \"" + printable(source, 1024) + "\"") + " at " +
              xyz + (is_finite(before) ? " is not finite after the transform" : " is not finite"));
    }
  }
  for (Vec3& n : mesh.normals) {
    n = N * n;
    if (reverse_orientation) n = -n;
  }
  if (!mesh.normals.empty() && mesh.normals.size() != mesh.positions.size())
    ps.fail("\"N\" has " + std::to_string(mesh.normals.size()) + " normals for " + std::to_string(mesh.positions.size()) + " vertices");
  if (!mesh.uvs.empty() && mesh.uvs.size() != mesh.positions.size())
    ps.fail("\"uv\" has " + std::to_string(mesh.uvs.size()) + " entries for " + std::to_string(mesh.positions.size()) + " vertices");
  for (size_t i = 0; i < mesh.triangle_count(); ++i) {
    const glm::uvec3 t = mesh.triangle(i);
    if (std::max({t.x, t.y, t.z}) >= mesh.positions.size())
      ps.fail("index " + std::to_string(std::max({t.x, t.y, t.z})) + " is out of range: there are " +
              std::to_string(mesh.positions.size()) + " vertices");
  }
  mesh.flip_normal = reverse_orientation != swaps_handedness(M);
  mesh.vertex_count = uint32_t(mesh.positions.size());
  if (mesh.triangle_count() > 0) mesh.positions.push_back(Vec3(0.f));  // Embree's 16-byte read of the last vertex
}

// A PLY mesh of parallelograms only (ply_patches found every quad one)
// keeps them as quads; the reader split each quad (a b c d) into (a b c)
// and (a c d), the order TriangleMesh::triangle gives them back in.
TriangleMesh from_ply(PlyMesh ply) {
  TriangleMesh m;
  m.positions = std::move(ply.positions);
  m.normals = std::move(ply.normals);
  m.uvs = std::move(ply.uvs);
  bool all_quads = !ply.triangles.empty() && ply.quad_first.size() * 2 == ply.triangles.size();
  for (size_t q = 0; all_quads && q < ply.quad_first.size(); ++q) all_quads = ply.quad_first[q] == 2 * q;
  if (!all_quads) {
    m.triangles = std::move(ply.triangles);
    return m;
  }
  m.quads.resize(ply.quad_first.size());
  for (size_t q = 0; q < m.quads.size(); ++q) {
    const glm::uvec3 a = ply.triangles[2 * q], b = ply.triangles[2 * q + 1];
    m.quads[q] = glm::uvec4(a.x, a.y, a.z, b.z);
  }
  return m;
}

void SceneBuilder::add_mesh(TriangleMesh mesh, const GraphicsState& gs, const ParamSet& ps, const std::string& source) {
  prepare_mesh(mesh, Mat4(gs.render_from_object), gs.reverse_orientation, ps, source);
  if (mesh.triangle_count() == 0) {
    warn(ps.where, ps.directive + " has no triangles and was skipped");
    return;
  }
  uint32_t prims = uint32_t(mesh.triangle_count());
  ShapePools& s = scene_.shapes;
  s.meshes.push_back(std::move(mesh));
  s.geometries.push_back({ShapeKind::Mesh, uint32_t(s.meshes.size() - 1), gs.material ? *gs.material : default_material(), -1, -1, {}});
  note_geometry();
  add_area_lights(uint32_t(s.geometries.size() - 1), prims, gs, ps);
}

// pbrt's "loopsubdiv": refined at load into a mesh with the limit
// surface's normals (geometry/loop_subdivision.h).
void SceneBuilder::add_subdivision_surface(const ParamSet& ps, const GraphicsState& gs) {
  const std::vector<Vec3> P = ps.get_point3s("P");
  const std::vector<int> indices = ps.get_ints("indices");
  if (P.empty()) ps.fail("\"point3 P\" is missing");
  if (indices.empty()) ps.fail("\"integer indices\" is missing");
  // pbrt-v3 called it "nlevels".
  const int levels = ps.has("levels") || !ps.has("nlevels") ? ps.get_int("levels", 3) : ps.get_int("nlevels", 3);
  SubdividedMesh sub;
  try {
    sub = loop_subdivide(P, indices, levels);
  } catch (const std::invalid_argument& e) {
    ps.fail(e.what());
  }
  TriangleMesh m;
  m.positions = std::move(sub.positions);
  m.normals = std::move(sub.normals);
  m.triangles = std::move(sub.triangles);
  add_mesh(std::move(m), gs, ps, "");
}

// A PLY mesh that does not emit is given its place in the pools now and is
// read later, with all the others in parallel (load_pending_meshes); an
// emitter needs its triangles at once, for the light table.
// A PLY mesh whose quads are not all parallelograms is a patch set, as in
// pbrt-v4 (scene/builder_patches.cpp).
void SceneBuilder::add_ply_mesh(const std::string& path, const GraphicsState& gs, const ParamSet& ps) {
  if (gs.area_light) {
    PlyMesh ply = read_ply(path);
    if (std::optional<BilinearPatchSet> patches = ply_patches(ply)) {
      prepare_patches(*patches, Mat4(gs.render_from_object), gs.reverse_orientation, ps, path);
      return add_patch_set(std::move(*patches), gs, ps);
    }
    return add_mesh(from_ply(std::move(ply)), gs, ps, path);
  }
  ShapePools& s = scene_.shapes;
  s.meshes.emplace_back();
  s.geometries.push_back({ShapeKind::Mesh, uint32_t(s.meshes.size() - 1), gs.material ? *gs.material : default_material(), -1, -1, {}});
  note_geometry();
  pending_.push_back({uint32_t(s.meshes.size() - 1), uint32_t(s.geometries.size() - 1), path, Mat4(gs.render_from_object),
                      gs.reverse_orientation, ps});
}

void SceneBuilder::load_pending_meshes() {
  if (pending_.empty()) return;
  if (progress_) progress_("reading " + std::to_string(pending_.size()) + " PLY meshes");
  // Errors are kept per mesh and the first in file order is reported, so
  // the message does not depend on thread timing.
  std::vector<std::exception_ptr> errors(pending_.size());
  std::vector<std::optional<BilinearPatchSet>> patches(pending_.size());
  tbb::parallel_for(size_t(0), pending_.size(), [&](size_t i) {
    const PendingMesh& p = pending_[i];
    try {
      PlyMesh ply = read_ply(p.path);
      patches[i] = ply_patches(ply);
      if (patches[i]) return prepare_patches(*patches[i], p.ctm, p.reverse_orientation, p.ps, p.path);
      TriangleMesh m = from_ply(std::move(ply));
      prepare_mesh(m, p.ctm, p.reverse_orientation, p.ps, p.path);
      scene_.shapes.meshes[p.mesh] = std::move(m);
    } catch (...) {
      errors[i] = std::current_exception();
    }
  });
  for (const std::exception_ptr& e : errors)
    if (e) std::rethrow_exception(e);
  ShapePools& s = scene_.shapes;
  for (size_t i = 0; i < pending_.size(); ++i) {
    const PendingMesh& p = pending_[i];
    if (patches[i]) {  // the geometry's place is kept; it now points at a patch set
      s.patches.push_back(std::move(*patches[i]));
      s.geometries[p.geometry].kind = ShapeKind::Bilinear;
      s.geometries[p.geometry].index = uint32_t(s.patches.size() - 1);
    } else if (s.meshes[p.mesh].triangle_count() == 0) {
      warn(p.ps.where, p.ps.directive + " has no triangles and was skipped");
    }
  }
  pending_.clear();
}

// Triangle counts, once every mesh is in: stored, inside objects, and as
// traced (objects once per instance).
void SceneBuilder::count_triangles() {
  const ShapePools& s = scene_.shapes;
  auto tris = [&](uint32_t g) {
    return s.geometries[g].kind == ShapeKind::Mesh ? s.meshes[s.geometries[g].index].triangle_count() : size_t(0);
  };
  scene_.triangle_count = scene_.prototype_triangle_count = scene_.instanced_triangle_count = 0;
  for (uint32_t g = 0; g < s.geometries.size(); ++g) {
    scene_.triangle_count += tris(g);
    if (g < s.in_prototype.size() && s.in_prototype[g]) scene_.prototype_triangle_count += tris(g);
  }
  std::vector<size_t> per_prototype(s.prototypes.size(), 0);
  for (size_t p = 0; p < s.prototypes.size(); ++p)
    for (uint32_t j = 0; j < s.prototypes[p].count; ++j) per_prototype[p] += tris(s.prototypes[p].first + j);
  for (const Placement& inst : s.instances) scene_.instanced_triangle_count += per_prototype[inst.prototype];
}

void SceneBuilder::shape(const std::string& type, const ParamSet& ps, const GraphicsState& gs, const std::string& base_dir) {
  if (gs.moving()) {
    moving_shape(type, ps, gs, base_dir);
    return;
  }
  const size_t before = scene_.shapes.geometries.size();
  add_shape(type, ps, gs, base_dir);
  assign_media(before, gs);
  assign_subsurface_media(before, gs, ps);
  // pbrt's "alpha": a float or a float texture; 1 (the default) is opaque.
  // A shape of "interface" material has no surface: unless it bounds a
  // medium (integrator/medium_*.h cross it), it is cut out entirely.
  FloatTextureRef alpha = float_texture(ps, "alpha", 1.f);
  const bool interface = gs.material && gs.material->kind() == MaterialKind::Interface;
  if (gs.area_light && interface) ps.fail("an emitting shape cannot have the \"interface\" material");
  if (interface && medium_interface(gs).transition()) {
    if (!alpha.is_constant() || alpha.value < 1.f) ps.fail(*ps.find("alpha"), "alpha on an \"interface\" shape is not supported");
    return;
  }
  if (interface) alpha = FloatTextureRef::constant(0.f);
  if (scene_.shapes.geometries.size() == before || (alpha.is_constant() && alpha.value >= 1.f)) return;
  if (gs.area_light)
    ps.fail(*ps.find("alpha"), "alpha on an emitting shape is not supported; cut the shape out of the light instead");
  ShapePools& s = scene_.shapes;
  s.geometries.back().alpha = int32_t(s.alpha_masks.size());
  s.alpha_masks.push_back({alpha});
}

void SceneBuilder::add_shape(const std::string& type, const ParamSet& ps, const GraphicsState& gs,
                             const std::string& base_dir) {
  if (type == "trianglemesh") {
    TriangleMesh m;
    m.positions = ps.get_point3s("P");
    m.normals = ps.get_point3s("N");
    m.uvs = ps.get_point2s(ps.has("uv") ? "uv" : "st");
    if (m.positions.empty()) ps.fail("\"point3 P\" is missing");
    std::vector<int> idx = ps.get_ints("indices");
    if (idx.empty() && m.positions.size() == 3) idx = {0, 1, 2};
    if (idx.empty()) ps.fail("\"integer indices\" is missing");
    if (idx.size() % 3 != 0)
      ps.fail("\"indices\" has " + std::to_string(idx.size()) + " values, expected a multiple of 3");
    for (int i : idx)
      if (i < 0) ps.fail("\"indices\" contains a negative index");
    for (size_t i = 0; i < idx.size(); i += 3) m.triangles.emplace_back(idx[i], idx[i + 1], idx[i + 2]);
    for (const char* p : {"S", "faceIndices"}) ps.find(p);
    add_mesh(std::move(m), gs, ps, "");
  } else if (type == "bilinearmesh") {
    add_bilinear_mesh(ps, gs);
  } else if (type == "loopsubdiv") {
    add_subdivision_surface(ps, gs);
  } else if (type == "plymesh") {
    std::string file = ps.get_string("filename", "");
    if (file.empty()) ps.fail("plymesh needs a \"filename\"");
    add_ply_mesh(resolve_path(base_dir, file), gs, ps);
  } else if (type == "sphere" || type == "cylinder" || type == "disk") {
    add_quadric(type, ps, gs);
  } else if (type == "curve") {
    add_curve(ps, gs);
  } else if (type == "heightfield") {  // pbrt-v3
    add_heightfield(ps, gs);
  } else if (type == "nurbs") {  // pbrt-v3
    add_nurbs(ps, gs);
  } else {
    ps.fail("shape \"" + printable(type) + "\" is not supported; expected trianglemesh, plymesh, bilinearmesh, "
            "loopsubdiv, sphere, cylinder, disk, curve, or pbrt-v3's heightfield or nurbs");
  }
}

void SceneBuilder::add_area_lights(uint32_t geometry, uint32_t primitives, const GraphicsState& gs,
                                   const pbrt::ParamSet& shape) {
  if (!gs.area_light) return;
  if (object_)
    gs.area_light->fail("area lights inside ObjectBegin/ObjectEnd are not supported (nor are they in pbrt-v4); "
                        "define the emitter outside the object");
  const ParamSet& ps = *gs.area_light;
  RGB L = ps.get_rgb("L", ColorUsage::Illuminant).value_or(RGB(1.f)) * light_scale(ps);
  bool two_sided = ps.get_bool("twosided", false);
  int32_t image = -1;
  if (std::string file = ps.get_string("filename", ""); !file.empty()) {
    // pbrt-v4: the image's RGB is the radiance, times "scale"; not with "L".
    if (ps.has("L")) ps.fail(*ps.find("L"), "give either \"L\" or \"filename\", not both");
    image = texture_image(ps, resolve_path(gs.area_light_dir, file), ColorEncoding{ColorEncoding::SRGB});
  }
  // "power": pbrt-v4 makes one light per primitive (each triangle of a
  // mesh, each patch) and gives each that power, normalised by its own area
  // and by the image's mean luminance (sRGB's Y weights).
  const bool by_power = ps.has("power");
  const float power = ps.get_float("power", 0.f);
  const int32_t spectrum = image < 0 ? light_spectrum(ps, "L") : -1;
  float image_luminance = 1.f;
  if (by_power && image >= 0) {
    double sum = 0.0;
    for (const RGB& t : scene_.textures.images[size_t(image)].texels) sum += double(luminance(t));
    image_luminance = float(sum / double(std::max<size_t>(1, scene_.textures.images[size_t(image)].texels.size())));
  }
  Geometry& g = scene_.shapes.geometries[geometry];
  g.light_offset = int32_t(scene_.lights.area.size());
  for (uint32_t i = 0; i < primitives; ++i) {
    float area = g.kind == ShapeKind::Mesh       ? triangle_area(scene_.shapes.meshes[g.index], i)
                 : g.kind == ShapeKind::Quadric  ? scene_.shapes.quadrics[g.index].world_area
                 : g.kind == ShapeKind::Bilinear ? bilinear_area(patch_corners(scene_.shapes.patches[g.index], i))
                                                 : 4.f * kPi * sqr(scene_.shapes.spheres[g.index].radius);
    RGB Li = L;
    const float k = (two_sided ? 2.f : 1.f) * area * kPi * image_luminance;
    if (by_power && k > 0.f) Li *= power / k;
    // An emitter whose area or power is beyond single precision: the light
    // sampler's sums and densities would be infinite, and the image too.
    if (!std::isfinite(area))
      shape.fail("primitive " + std::to_string(i) +
                 " of this emitting shape has an area beyond single precision (sides of about 1e19 or more)");
    if (!std::isfinite(k * max_component(Li)))
      shape.fail("primitive " + std::to_string(i) +
                 " of this emitting shape sends a power beyond single precision (its radiance times its area)");
    scene_.lights.area.push_back({geometry, i, Li, two_sided, area, image, spectrum});
  }
  ps.warn_unused();
}

// Geometry just appended: it belongs to the object being defined, if any.
void SceneBuilder::note_geometry() {
  ShapePools& s = scene_.shapes;
  s.in_prototype.push_back(object_ ? 1 : 0);
  if (!object_) return;
  Prototype& proto = s.prototypes[object_->prototype];
  if (proto.count == 0) proto.first = uint32_t(s.geometries.size() - 1);
  ++proto.count;
}

void SceneBuilder::begin_object(const std::string& name, const SourceLocation& where) {
  if (object_) throw InputError(where, "ObjectBegin \"" + printable(name) + "\" inside ObjectBegin \"" +
                                            printable(object_->name) + "\": objects cannot nest");
  if (objects_.count(name)) throw InputError(where, "object \"" + printable(name) + "\" is defined twice");
  scene_.shapes.prototypes.push_back({});
  object_ = OpenObject{name, uint32_t(scene_.shapes.prototypes.size() - 1)};
  object_where_ = where;
}

void SceneBuilder::end_object(const SourceLocation& where) {
  if (!object_) throw InputError(where, "ObjectEnd without ObjectBegin");
  objects_[object_->name] = object_->prototype;
  object_.reset();
}

void SceneBuilder::check_objects_closed() const {
  if (object_) throw InputError(object_where_, "ObjectBegin \"" + printable(object_->name) + "\" without ObjectEnd");
}

}  // namespace lantern
