// Shape "bilinearmesh", with pbrt-v4's parameters: P, indices (four per
// patch, p00 p10 p01 p11; [0 1 2 3] when P has four points), N, uv.
// A mesh whose every patch is a parallelogram (positions, and normals and
// uvs if given) is an affine image of the square: exactly two triangles per
// patch, traced as a triangle mesh. Any other mesh keeps its patches
// (geometry/bilinear_patch.h).
#include <glm/gtc/matrix_inverse.hpp>

#include "scene/builder.h"
#include "scene/ply.h"

namespace lantern {

using pbrt::ParamSet;

bool swaps_handedness(const Mat4& m);  // builder.cpp

namespace {

Vec3 as_vec3(const Vec3& v) { return v; }
Vec3 as_vec3(const Vec2& v) { return Vec3(v, 0.f); }

template <class V>
bool parallelograms(const std::vector<V>& a, const std::vector<int>& idx) {
  if (a.empty()) return true;
  auto at = [&](size_t i) { return as_vec3(a[size_t(idx[i])]); };
  for (size_t i = 0; i < idx.size(); i += 4)
    if (!is_parallelogram(at(i), at(i + 1), at(i + 2), at(i + 3))) return false;
  return true;
}

// Two triangles per patch (split along p00-p11). Without uvs each patch
// gets its own four corners to carry its (u, v), which run over [0,1]^2
// from p00 to p11 as in pbrt-v4.
TriangleMesh split_patches(std::vector<Vec3> P, std::vector<Vec3> N, std::vector<Vec2> uv, std::vector<int> idx) {
  TriangleMesh m;
  if (uv.empty()) {
    const bool with_n = N.size() == P.size();
    for (size_t i = 0; i < idx.size(); ++i) {
      m.positions.push_back(P[size_t(idx[i])]);
      if (with_n) m.normals.push_back(N[size_t(idx[i])]);
      m.uvs.emplace_back(float(i % 4 & 1), float(i % 4 >> 1));
    }
    if (!with_n) m.normals = std::move(N);  // left for add_mesh to check
    for (size_t i = 0; i < idx.size(); ++i) idx[i] = int(i);
  } else {
    m.positions = std::move(P);
    m.normals = std::move(N);
    m.uvs = std::move(uv);
  }
  for (size_t i = 0; i < idx.size(); i += 4) {
    m.triangles.emplace_back(idx[i], idx[i + 1], idx[i + 3]);
    m.triangles.emplace_back(idx[i], idx[i + 3], idx[i + 2]);
  }
  return m;
}

}  // namespace

void SceneBuilder::add_bilinear_mesh(const ParamSet& ps, const GraphicsState& gs) {
  std::vector<Vec3> P = ps.get_point3s("P"), N = ps.get_point3s("N");
  std::vector<Vec2> uv = ps.get_point2s(ps.has("uv") ? "uv" : "st");
  if (P.empty()) ps.fail("\"point3 P\" is missing");
  std::vector<int> idx = ps.get_ints("indices");
  if (idx.empty() && P.size() == 4) idx = {0, 1, 2, 3};
  if (idx.empty()) ps.fail("\"integer indices\" is missing");
  if (idx.size() % 4 != 0)
    ps.fail("\"indices\" has " + std::to_string(idx.size()) + " values, expected a multiple of 4");
  for (int i : idx)
    if (i < 0 || size_t(i) >= P.size())
      ps.fail("index " + std::to_string(i) + " is out of range: there are " + std::to_string(P.size()) + " vertices");
  if (!N.empty() && N.size() != P.size())
    ps.fail("\"N\" has " + std::to_string(N.size()) + " normals for " + std::to_string(P.size()) + " vertices");
  if (!uv.empty() && uv.size() != P.size())
    ps.fail("\"uv\" has " + std::to_string(uv.size()) + " entries for " + std::to_string(P.size()) + " vertices");
  for (const char* p : {"S", "faceIndices"}) ps.find(p);
  if (parallelograms(P, idx) && parallelograms(N, idx) && parallelograms(uv, idx))
    return add_mesh(split_patches(std::move(P), std::move(N), std::move(uv), std::move(idx)), gs, ps, "");

  BilinearPatchSet s;
  s.positions = std::move(P);
  s.normals = std::move(N);
  s.uvs = std::move(uv);
  for (size_t i = 0; i < idx.size(); i += 4) s.patches.emplace_back(idx[i], idx[i + 1], idx[i + 2], idx[i + 3]);
  prepare_patches(s, Mat4(gs.render_from_object), gs.reverse_orientation, ps, "");
  add_patch_set(std::move(s), gs, ps);
}

void SceneBuilder::add_patch_set(BilinearPatchSet s, const GraphicsState& gs, const ParamSet& ps) {
  const uint32_t count = uint32_t(s.patches.size());
  ShapePools& pools = scene_.shapes;
  pools.patches.push_back(std::move(s));
  pools.geometries.push_back(
      {ShapeKind::Bilinear, uint32_t(pools.patches.size() - 1), gs.material ? *gs.material : default_material(), -1, -1, {}});
  note_geometry();
  add_area_lights(uint32_t(pools.geometries.size() - 1), count, gs, ps);
}

void prepare_patches(BilinearPatchSet& s, const Mat4& M, bool reverse_orientation, const ParamSet& ps,
                     const std::string& source) {
  const glm::mat3 to_normal = glm::inverseTranspose(glm::mat3(M));
  const std::string of = source.empty() ? "" : " of \"" + printable(source, 1024) + "\"";
  for (size_t i = 0; i < s.positions.size(); ++i) {
    const Vec3 p = Vec3(M * Vec4(s.positions[i], 1.f));
    if (!is_finite(p))
      ps.fail("vertex " + std::to_string(i) + of + " is not finite" + (is_finite(s.positions[i]) ? " after the transform" : ""));
    s.positions[i] = p;
  }
  for (Vec3& n : s.normals) n = reverse_orientation ? -(to_normal * n) : to_normal * n;
  if (!s.normals.empty() && s.normals.size() != s.positions.size())
    ps.fail("\"N\" has " + std::to_string(s.normals.size()) + " normals for " + std::to_string(s.positions.size()) + " vertices" + of);
  if (!s.uvs.empty() && s.uvs.size() != s.positions.size())
    ps.fail("\"uv\" has " + std::to_string(s.uvs.size()) + " entries for " + std::to_string(s.positions.size()) + " vertices" + of);
  for (const glm::uvec4& q : s.patches)
    if (std::max({q.x, q.y, q.z, q.w}) >= s.positions.size())
      ps.fail("index " + std::to_string(std::max({q.x, q.y, q.z, q.w})) + of + " is out of range: there are " +
              std::to_string(s.positions.size()) + " vertices");
  s.flip_normal = reverse_orientation != swaps_handedness(M);
}

std::optional<BilinearPatchSet> ply_patches(const PlyMesh& ply) {
  if (ply.quad_first.empty()) return std::nullopt;
  // A quad (v0 v1 v2 v3) read around its face is the patch (v0 v1 v3 v2).
  std::vector<int> idx;
  std::vector<uint8_t> in_quad(ply.triangles.size(), 0);
  for (uint32_t t : ply.quad_first) {
    const glm::uvec3 a = ply.triangles[t], b = ply.triangles[t + 1];
    idx.insert(idx.end(), {int(a.x), int(a.y), int(b.z), int(a.z)});
    in_quad[t] = in_quad[t + 1] = 1;
  }
  for (int i : idx)
    if (size_t(i) >= ply.positions.size()) return std::nullopt;  // prepare_mesh names the bad index
  const bool with_n = ply.normals.size() == ply.positions.size(), with_uv = ply.uvs.size() == ply.positions.size();
  if (parallelograms(ply.positions, idx) && (!with_n || parallelograms(ply.normals, idx)) &&
      (!with_uv || parallelograms(ply.uvs, idx)))
    return std::nullopt;
  BilinearPatchSet s;
  s.positions = ply.positions;
  s.normals = ply.normals;
  s.uvs = ply.uvs;
  for (size_t i = 0; i < idx.size(); i += 4) s.patches.emplace_back(idx[i], idx[i + 1], idx[i + 2], idx[i + 3]);
  s.first_triangle = uint32_t(s.patches.size());
  for (size_t t = 0; t < ply.triangles.size(); ++t)
    if (!in_quad[t]) s.patches.emplace_back(ply.triangles[t].x, ply.triangles[t].y, ply.triangles[t].z, ply.triangles[t].z);
  return s;
}

}  // namespace lantern
