// Bilinear patches (geometry/bilinear_patch.h): ray hits against a brute-force
// search of a fine tessellation, area and sampling density against
// independent quadrature, emission in all three integrators, a scene
// against pbrt-v4, and parallelograms staying triangles.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "expect_error.h"
#include "lantern/render.h"
#include "lantern/scene.h"
#include "math/rng.h"
#include "sanitizer.h"
#include "scene/scene.h"
#include "geometry/surface.h"
#include "stat_compare.h"

namespace lantern {
namespace {

const PatchCorners kSaddle{Vec3(0, 0, 0), Vec3(1, 0, 0.2f), Vec3(0, 1, 0.1f), Vec3(1.2f, 1.1f, 1.f)};

Vec3 patch_at(const PatchCorners& c, float u, float v) {
  return glm::mix(glm::mix(c.p00, c.p10, u), glm::mix(c.p01, c.p11, u), v);
}

// The first crossing of a ray with an n x n tessellation of the patch
// (Moller-Trumbore on each triangle): a reference that shares nothing with
// the quadratic the patch test solves.
bool brute_force_hit(const PatchCorners& c, const Vec3& o, const Vec3& d, int n, float* t_hit) {
  bool found = false;
  *t_hit = kInfinity;
  auto tri = [&](const Vec3& a, const Vec3& b, const Vec3& q) {
    const Vec3 e1 = b - a, e2 = q - a, pv = glm::cross(d, e2);
    const float det = glm::dot(e1, pv);
    if (std::fabs(det) < 1e-12f) return;
    const Vec3 tv = o - a;
    const float u = glm::dot(tv, pv) / det;
    const Vec3 qv = glm::cross(tv, e1);
    const float v = glm::dot(d, qv) / det, t = glm::dot(e2, qv) / det;
    if (u < 0.f || v < 0.f || u + v > 1.f || !(t > 1e-6f) || t >= *t_hit) return;
    *t_hit = t;
    found = true;
  };
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const float u0 = float(i) / float(n), u1 = float(i + 1) / float(n), v0 = float(j) / float(n),
                  v1 = float(j + 1) / float(n);
      const Vec3 a = patch_at(c, u0, v0), b = patch_at(c, u1, v0), q = patch_at(c, u0, v1), r = patch_at(c, u1, v1);
      tri(a, b, r);
      tri(a, r, q);
    }
  return found;
}

TEST(BilinearPatch, HitsMatchABruteForceSearch) {
  RandomStream rng = RandomStream::make(4, 0, 0);
  const int rays = LANTERN_ASAN ? 60 : 400, n = 96;
  int hits = 0;
  for (int k = 0; k < rays; ++k) {
    // From around the patch towards a point near it: hits, misses, grazing
    // rays and rays that cross the saddle twice.
    const Vec3 o(3.f * rng.get1d() - 1.f, 3.f * rng.get1d() - 1.f, 4.f * rng.get1d() - 1.5f);
    const Vec3 target(1.4f * rng.get1d() - 0.2f, 1.4f * rng.get1d() - 0.2f, 1.2f * rng.get1d() - 0.1f);
    const Vec3 d = glm::normalize(target - o);
    double t;
    Vec2 uv;
    const bool hit = intersect_bilinear_patch(kSaddle, glm::dvec3(o), glm::dvec3(d), 0.0, 1e30, &t, &uv);
    float t_ref;
    const bool ref = brute_force_hit(kSaddle, o, d, n, &t_ref);
    if (hit != ref) {
      // Only rays through the rim may disagree with a tessellation.
      const float rim = std::fmin(std::fmin(uv.x, 1.f - uv.x), std::fmin(uv.y, 1.f - uv.y));
      EXPECT_TRUE(hit && rim < 0.02f) << "ray " << k << ": patch " << hit << ", tessellation " << ref;
      continue;
    }
    if (!hit) continue;
    ++hits;
    // The chords of the tessellation sit within about (1 / n)^2 of the patch.
    EXPECT_NEAR(float(t), t_ref, 2e-3f * std::fmax(1.f, t_ref)) << "ray " << k;
    EXPECT_LT(glm::length(patch_at(kSaddle, uv.x, uv.y) - (o + float(t) * d)), 1e-4f) << "ray " << k;
  }
  EXPECT_GT(hits, rays / 5);
}

TEST(BilinearPatch, AreaAndSamplingDensityIntegrate) {
  // Area: the library's 4x4 Gauss-Legendre rule against a 400x400 midpoint rule.
  double area = 0.0;
  const int m = 400;
  for (int j = 0; j < m; ++j)
    for (int i = 0; i < m; ++i)
      area += double(glm::length(patch_cross(kSaddle, Vec2((float(i) + 0.5f) / m, (float(j) + 0.5f) / m)))) / (m * m);
  EXPECT_NEAR(bilinear_area(kSaddle), area, 1e-4 * area);
  // The density per area integrates to 1 (uniform (u, v), weighted by the
  // Jacobian), and E[f / density] over sampled points is the integral of f.
  RandomStream rng = RandomStream::make(5, 0, 0);
  const int n = 200000;
  double total = 0.0, by_sampling = 0.0, by_uniform = 0.0;
  for (int k = 0; k < n; ++k) {
    const Vec2 uv(rng.get1d(), rng.get1d());
    const float jac = glm::length(patch_cross(kSaddle, uv));
    total += double(bilinear_area_density(kSaddle, uv) * jac);
    const Vec3 p = patch_at(kSaddle, uv.x, uv.y);
    by_uniform += double((1.f + p.x * p.x) * jac);
    const Vec2 s = sample_bilinear_patch(kSaddle, Vec2(rng.get1d(), rng.get1d()));
    const Vec3 q = patch_at(kSaddle, s.x, s.y);
    by_sampling += double(1.f + q.x * q.x) / double(bilinear_area_density(kSaddle, s));
    // A sampled point's (u, v) is found again from the point alone.
    if (k < 2000) EXPECT_LT(glm::length(bilinear_uv_of(kSaddle, q) - s), 1e-4f);
  }
  EXPECT_NEAR(total / n, 1.0, 2e-3);
  EXPECT_NEAR(by_sampling / by_uniform, 1.0, 5e-3);
}

// A curved one-sided emitter over a floor: next-event estimation samples it
// by area, light subpaths start on it, bdpt weighs both by its density.
TEST(BilinearPatch, IntegratorsAgreeUnderACurvedPatchLight) {
  if (LANTERN_ASAN) GTEST_SKIP() << "the Release suite runs it; the sanitizers cover the patch code above";
  auto scene = load_scene_from_string(R"(
LookAt 0 -4 2.5  0 0 0.3  0 0 1
Camera "perspective" "float fov" [ 40 ]
WorldBegin
AttributeBegin
  AreaLightSource "diffuse" "rgb L" [ 4 3 2 ]
  Shape "bilinearmesh" "point3 P" [ -0.8 -0.6 1.9  0.8 -0.6 1.5  -0.8 0.7 1.5  0.9 0.7 2.1 ]
AttributeEnd
Material "diffuse" "rgb reflectance" [ 0.6 0.6 0.6 ]
Shape "trianglemesh" "point3 P" [ -6 -6 0 6 -6 0 6 6 0 -6 6 0 ] "integer indices" [ 0 1 2 0 2 3 ]
AttributeBegin
  Material "diffuse" "rgb reflectance" [ 0.3 0.5 0.7 ]
  Shape "bilinearmesh" "point3 P" [ -0.5 -0.5 0  0.5 -0.5 0.8  -0.5 0.5 0.8  0.5 0.5 0 ]
AttributeEnd
)",
                                      "patch-light.pbrt");
  const std::vector<Region> regions = {{0, 0, 24, 24}, {6, 6, 12, 12}, {0, 16, 12, 8}, {12, 16, 12, 8}, {0, 0, 24, 6}};
  auto path = render_stats(*scene, "path", 24, 24, 32, 12, regions);
  auto bdpt = render_stats(*scene, "bdpt", 24, 24, 16, 12, regions);
  auto lt = render_stats(*scene, "lt", 24, 24, 32, 12, regions);
  EXPECT_LT(max_z(bdpt, path), 5.0);
  EXPECT_LT(max_z(lt, path), 5.0);
}

// perf/shapes/bilinear.pbrt at 32x24 against pbrt-v4's region means
// (pbrt-v4 with the film set to 32x24 and 16384 spp, means by oiiotool
// --cut --printstats): the whole image, the checkered trapezoid (split
// into two triangles its checks bend at the diagonal), the saddle, the
// wavy mesh with normals and the emitter. 2% beyond the noise.
TEST(BilinearPatch, SceneMatchesPbrt) {
  if (LANTERN_ASAN) GTEST_SKIP() << "the Release suite runs it";
  auto scene = load_scene(std::string(LANTERN_SOURCE_DIR) + "/perf/shapes/bilinear.pbrt");
  const std::vector<Region> regions = {{0, 0, 32, 24}, {19, 13, 12, 7}, {5, 7, 8, 8}, {16, 8, 6, 5}, {6, 0, 10, 2}};
  const std::vector<std::array<double, 3>> pbrt = {{0.265421, 0.242094, 0.219802},
                                                   {0.171563, 0.125828, 0.109952},
                                                   {0.079142, 0.107574, 0.126737},
                                                   {0.116397, 0.105706, 0.063399},
                                                   {3.757495, 3.159766, 2.561438}};
  expect_matches_pbrt(*scene, 32, 24, 5, 64, 6, regions, pbrt);
}

// Parallelograms are two triangles exactly and stay a triangle mesh (no
// user geometry to pay for); any other patch keeps its own shape.
TEST(BilinearPatch, OnlyCurvedOrSkewedPatchesAreTracedAsPatches) {
  auto kinds = [](const std::string& shape) {
    auto scene = load_scene_from_string("WorldBegin\n" + shape + "\n", "kinds.pbrt");
    return scene->shapes.geometries.at(0).kind;
  };
  EXPECT_EQ(kinds(R"(Shape "bilinearmesh" "point3 P" [ 0 0 0  2 0 0  0.5 1 1  2.5 1 1 ])"), ShapeKind::Mesh);
  EXPECT_EQ(kinds(R"(Shape "bilinearmesh" "point3 P" [ 0 0 0  2 0 0  0 1 0  1 1 0 ])"), ShapeKind::Bilinear);
  EXPECT_EQ(kinds(R"(Shape "bilinearmesh" "point3 P" [ 0 0 0  1 0 0  0 1 0  1 1 0 ] "point2 uv" [ 0 0 1 0 0 1 2 2 ])"),
            ShapeKind::Bilinear);
  EXPECT_EQ(kinds(R"(Shape "bilinearmesh" "point3 P" [ 0 0 0  1 0 0  0 1 0  1 1 0.5 ])"), ShapeKind::Bilinear);
}

// PLY quads are patches as in pbrt-v4 (v0 v1 v2 v3 around the face is the
// patch v0 v1 v3 v2) when any is not a parallelogram; the file's triangles
// then become patches that collapse an edge, which are those triangles. A
// PLY of flat parallelograms stays a triangle mesh. Both read back as the
// same surfaces given directly: the same image.
TEST(BilinearPatch, PlyQuadsArePatchesUnlessParallelograms) {
  const auto dir = std::filesystem::temp_directory_path() / "lantern-ply-quads";
  std::filesystem::create_directories(dir);
  auto ply = [&](const std::string& name, const std::string& vertices, const std::string& faces, int nv, int nf) {
    const std::string path = (dir / name).string();
    std::ofstream(path) << "ply\nformat ascii 1.0\nelement vertex " << nv
                        << "\nproperty float x\nproperty float y\nproperty float z\nelement face " << nf
                        << "\nproperty list uchar int vertex_indices\nend_header\n"
                        << vertices << faces;
    return path;
  };
  const std::string curved = ply("curved.ply", "-1 -1 0\n1 -1 0.6\n1 1 0\n-1 1 0.6\n0 2 0.3\n", "4 0 1 2 3\n3 3 2 4\n", 5, 2);
  const std::string flat = ply("flat.ply", "-1 -1 0\n1 -1 0\n1 1 0\n-1 1 0\n", "4 0 1 2 3\n", 4, 1);
  const std::string head = R"(LookAt 0 -4 3  0 0 0.2  0 0 1
Camera "perspective" "float fov" [ 45 ]
Film "rgb" "integer xresolution" [ 24 ] "integer yresolution" [ 24 ]
WorldBegin
LightSource "distant" "point3 from" [ 1 -2 3 ] "point3 to" [ 0 0 0 ] "rgb L" [ 2 2 2 ]
)";
  auto from_ply = load_scene_from_string(head + "Shape \"plymesh\" \"string filename\" \"" + curved + "\"\n", "ply.pbrt");
  ASSERT_EQ(from_ply->shapes.geometries.size(), 1u);
  EXPECT_EQ(from_ply->shapes.geometries[0].kind, ShapeKind::Bilinear);
  const BilinearPatchSet& s = from_ply->shapes.patches.at(0);
  ASSERT_EQ(s.patches.size(), 2u);
  EXPECT_EQ(s.patches[0], glm::uvec4(0, 1, 3, 2));
  EXPECT_EQ(s.patches[1], glm::uvec4(3, 2, 4, 4));
  auto direct = load_scene_from_string(head + R"(Shape "bilinearmesh" "point3 P" [ -1 -1 0  1 -1 0.6  1 1 0  -1 1 0.6  0 2 0.3 ]
  "integer indices" [ 0 1 3 2  3 2 4 4 ]
)",
                                       "direct.pbrt");
  expect_identical_renders(*from_ply, *direct, {"path", "bdpt"});
  auto planar = load_scene_from_string(head + "Shape \"plymesh\" \"string filename\" \"" + flat + "\"\n", "flat.pbrt");
  EXPECT_EQ(planar->shapes.geometries.at(0).kind, ShapeKind::Mesh);
}

// perf/shapes/plyquads.pbrt at 32x24 against pbrt-v4's region means
// (pbrt-v4 with the film set to 32x24 and 16384 spp, means by oiiotool
// --cut --printstats): the whole image, four patches of the checkered wavy
// grid (PLY quads as patches, with their own (u, v); split into triangles
// the checks shift and the test fails), and the triangle fan (pbrt's
// default triangle uvs).
TEST(BilinearPatch, PlyQuadsMatchPbrt) {
  if (LANTERN_ASAN) GTEST_SKIP() << "the Release suite runs it";
  auto scene = load_scene(std::string(LANTERN_SOURCE_DIR) + "/perf/shapes/plyquads.pbrt");
  const std::vector<Region> regions = {{0, 0, 32, 24}, {8, 10, 4, 4}, {12, 10, 4, 4}, {16, 10, 4, 4}, {20, 10, 4, 4}, {10, 4, 8, 4}};
  const std::vector<std::array<double, 3>> pbrt = {{0.381095, 0.344007, 0.322100}, {0.575882, 0.413864, 0.316956},
                                                   {0.647003, 0.456985, 0.342400}, {0.637665, 0.444733, 0.330505},
                                                   {0.550003, 0.390778, 0.297874}, {0.453362, 0.385117, 0.347588}};
  expect_matches_pbrt(*scene, 32, 24, 5, 64, 6, regions, pbrt);
}

TEST(BilinearPatch, BadMeshesGiveClearErrors) {
  const std::string head = "WorldBegin\nShape \"bilinearmesh\" ";
  expect_load_error(head + R"("point3 P" [0 0 0 1 0 0 0 1 0 1 1 1] "integer indices" [0 1 2 4])", "range.pbrt",
                    {"range.pbrt:2", "index 4 is out of range"});
  expect_load_error(head + R"("point3 P" [0 0 0 1 0 0 0 1 0 1 1 1] "integer indices" [0 1 2])", "count.pbrt",
                    {"count.pbrt:2", "multiple of 4"});
  expect_load_error(head + R"("point3 P" [0 0 0 1 0 0 0 1 0 1 1 1] "normal N" [0 0 1])", "normals.pbrt",
                    {"normals.pbrt:2", "1 normals for 4 vertices"});
  expect_load_error(head + R"("point3 P" [0 0 0 1 0 0 0 1 0 1 1 1 0 0 0])", "noidx.pbrt",
                    {"noidx.pbrt:2", "indices", "missing"});
}

}  // namespace
}  // namespace lantern
