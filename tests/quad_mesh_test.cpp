// A PLY mesh of parallelograms is kept as quads and traced as Embree quads;
// every reader sees it as the triangles the PLY's quads split into. The
// same surfaces given as a trianglemesh must give the same hits (point,
// normals, uv, triangle) and the same image, also with an alpha texture
// (whose filter runs on Embree's quad hits) and when the quads emit
// (pbrt-v4 allows no alpha on an emitter).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "accel/ray_stream.h"
#include "integrator/hit.h"
#include "lantern/render.h"
#include "lantern/scene.h"
#include "math/rng.h"
#include "scene/scene.h"
#include "stat_compare.h"

namespace lantern {
namespace {

// A sheared 3 x 2 grid of parallelograms far from the origin (where a
// corner's rounding is largest), with uvs, and a vertical panel.
struct Grid {
  std::vector<Vec3> p;
  std::vector<Vec2> uv;
  std::vector<glm::uvec4> quads;  // around each face
};

Grid make_grid() {
  Grid g;
  const Vec3 o(1000.f, 0.f, -1000.f), du(0.7f, 0.f, 0.15f), dv(0.2f, 0.05f, 0.6f);
  for (int j = 0; j <= 2; ++j)
    for (int i = 0; i <= 3; ++i) {
      g.p.push_back(o + float(i) * du + float(j) * dv);
      g.uv.push_back(Vec2(0.25f * float(i), 0.5f * float(j)));
    }
  for (uint32_t j = 0; j < 2; ++j)
    for (uint32_t i = 0; i < 3; ++i) {
      const uint32_t a = j * 4 + i;
      g.quads.push_back({a, a + 1, a + 5, a + 4});
    }
  const uint32_t b = uint32_t(g.p.size());
  for (Vec3 q : {Vec3(0, 0, 1.4f), Vec3(2, 0, 1.4f), Vec3(2, 1.2f, 1.4f), Vec3(0, 1.2f, 1.4f)}) {
    g.p.push_back(o + q);
    g.uv.push_back(Vec2(q.x * 0.5f, q.y / 1.2f));
  }
  g.quads.push_back({b, b + 1, b + 2, b + 3});
  return g;
}

// (A file per test: ctest runs the tests of this file side by side.)
std::string write_ply(const Grid& g) {
  const auto path =
      std::filesystem::temp_directory_path() /
      ("lantern-quad-mesh-" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()) + ".ply");
  std::ofstream f(path);
  f << "ply\nformat ascii 1.0\nelement vertex " << g.p.size()
    << "\nproperty float x\nproperty float y\nproperty float z\nproperty float u\nproperty float v\nelement face "
    << g.quads.size() << "\nproperty list uchar int vertex_indices\nend_header\n";
  f.precision(9);
  for (size_t i = 0; i < g.p.size(); ++i)
    f << g.p[i].x << " " << g.p[i].y << " " << g.p[i].z << " " << g.uv[i].x << " " << g.uv[i].y << "\n";
  for (const glm::uvec4& q : g.quads) f << "4 " << q.x << " " << q.y << " " << q.z << " " << q.w << "\n";
  return path.string();
}

// The grid as a trianglemesh split as the PLY reader splits it.
std::string as_trianglemesh(const Grid& g) {
  std::ostringstream t;
  t.precision(9);
  t << "Shape \"trianglemesh\" \"point3 P\" [";
  for (const Vec3& p : g.p) t << " " << p.x << " " << p.y << " " << p.z;
  t << " ] \"point2 uv\" [";
  for (const Vec2& uv : g.uv) t << " " << uv.x << " " << uv.y;
  t << " ] \"integer indices\" [";
  for (const glm::uvec4& q : g.quads) t << " " << q.x << " " << q.y << " " << q.z << " " << q.x << " " << q.z << " " << q.w;
  t << " ]";
  return t.str();
}

std::string scene_text(const std::string& shape, const std::string& attributes) {
  return "Option \"string renderingcoordinatesystem\" \"world\"\n"
         "LookAt 1001.5 3 -1002.5  1001.2 0.3 -999.5  0 1 0\nCamera \"perspective\" \"float fov\" [ 50 ]\n"
         "Film \"rgb\" \"integer xresolution\" [ 24 ] \"integer yresolution\" [ 16 ]\n"
         "WorldBegin\nLightSource \"infinite\" \"rgb L\" [ 0.3 0.3 0.35 ]\n"
         "LightSource \"distant\" \"point3 from\" [ 0 1 0.3 ] \"point3 to\" [ 0 0 0 ] \"rgb L\" [ 2 2 2 ]\n"
         "Texture \"checks\" \"float\" \"checkerboard\" \"float uscale\" 4 \"float vscale\" 4 \"float tex1\" 0 \"float tex2\" 1\n"
         "Texture \"colours\" \"spectrum\" \"checkerboard\" \"float uscale\" 6 \"float vscale\" 3 "
         "\"rgb tex1\" [ 0.8 0.2 0.1 ] \"rgb tex2\" [ 0.1 0.3 0.8 ]\n"
         "AttributeBegin\n" + attributes + "Material \"diffuse\" \"texture reflectance\" \"colours\"\n" + shape +
         "\nAttributeEnd\n";
}

TEST(QuadMesh, PlyParallelogramsAreEmbreeQuadsWithTheTrianglesHits) {
  const Grid g = make_grid();
  const std::string ply = "Shape \"plymesh\" \"string filename\" \"" + write_ply(g) + "\"";
  auto quads = load_scene_from_string(scene_text(ply, ""), "quads.pbrt");
  auto tris = load_scene_from_string(scene_text(as_trianglemesh(g), ""), "tris.pbrt");
  ASSERT_EQ(quads->shapes.meshes.size(), 1u);
  EXPECT_EQ(quads->shapes.meshes[0].quads.size(), g.quads.size());
  EXPECT_TRUE(quads->shapes.meshes[0].triangles.empty());
  EXPECT_EQ(scene_info(*quads).triangles, 2 * g.quads.size());
  for (const char* backend : {"stream", "single", "packet16"}) {
    SCOPED_TRACE(backend);
    RayBatch a, b;
    RandomStream s = RandomStream::make(3, 0, 0);
    for (int i = 0; i < 4000; ++i) {
      const Vec3 o(1001.2f + 2.f * s.get1d() - 1.f, 2.f + s.get1d(), -1001.f + 2.f * s.get1d() - 1.f);
      const Vec3 target(1000.f + 2.5f * s.get1d(), 0.6f * s.get1d(), -1000.f + 1.6f * s.get1d());
      a.push(o, target - o, 0.f, 1e30f, 0.f);
      b.push(o, target - o, 0.f, 1e30f, 0.f);
    }
    RayStream qa(quads->accel->handle(), parse_ray_backend(backend), nullptr);
    qa.set_scene(quads->accel->instance_base(), &quads->shapes);
    qa.intersect(a, RayKind::Extension);
    RayStream tb(tris->accel->handle(), parse_ray_backend(backend), nullptr);
    tb.set_scene(tris->accel->instance_base(), &tris->shapes);
    tb.intersect(b, RayKind::Extension);
    int compared = 0, disagree = 0;
    for (uint32_t i = 0; i < a.count; ++i) {
      if (a.hit(i) != b.hit(i) || (a.hit(i) && a.prim_id[i] != b.prim_id[i])) {
        ++disagree;  // grazing an edge or the diagonal: rounding may decide either way
        continue;
      }
      if (!a.hit(i)) continue;
      ++compared;
      const SurfacePoint pa = hit_point(quads->shapes, a, i), pb = hit_point(tris->shapes, b, i);
      // Ten float steps at 1000: the quad's and the triangle's intersection
      // tests round differently.
      ASSERT_LT(glm::length(pa.p - pb.p), 6e-4f) << "ray " << i;
      ASSERT_GT(glm::dot(pa.ng, pb.ng), 0.99999f) << "ray " << i;
      ASSERT_LT(glm::length(pa.uv - pb.uv), 1e-4f) << "ray " << i;
    }
    EXPECT_GT(compared, 2000);
    EXPECT_LT(disagree, 20);
  }
}

TEST(QuadMesh, QuadsRenderAsTheirTrianglesWithAlphaAndEmission) {
  const Grid g = make_grid();
  const std::string ply = "Shape \"plymesh\" \"string filename\" \"" + write_ply(g) + "\"";
  const std::vector<Region> regions = {{0, 0, 24, 16}, {0, 0, 12, 8}, {12, 0, 12, 8}, {0, 8, 12, 8}, {12, 8, 12, 8}};
  for (const std::string& attributes :
       {std::string(""), std::string("AreaLightSource \"diffuse\" \"rgb L\" [ 2 1.5 1 ]\n")}) {
    for (const std::string& alpha : {std::string(""), std::string(" \"texture alpha\" \"checks\"")}) {
      if (!attributes.empty() && !alpha.empty()) continue;
      SCOPED_TRACE(attributes + alpha);
      auto quads = load_scene_from_string(scene_text(ply + alpha, attributes), "quads.pbrt");
      auto tris = load_scene_from_string(scene_text(as_trianglemesh(g) + alpha, attributes), "tris.pbrt");
      for (const char* integrator : {"path", "bdpt"}) {
        SCOPED_TRACE(integrator);
        const RegionStats sq = render_stats(*quads, integrator, 24, 16, 8, 6, regions);
        const RegionStats st = render_stats(*tris, integrator, 24, 16, 8, 6, regions);
        EXPECT_GT(st.mean[0][0], 0.01);
        EXPECT_LT(max_z(sq, st), 5.0);
      }
    }
  }
}

}  // namespace
}  // namespace lantern
