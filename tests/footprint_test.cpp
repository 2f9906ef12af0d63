// Pixel footprints from the camera against the geometry of a pinhole camera
// looking at planes, and textures filtered over them rendering the same
// image with path tracing, bidirectional path tracing and light tracing.
#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>

#include "lantern/image.h"
#include "scene/scene.h"
#include "geometry/shading_geometry.h"
#include "stat_compare.h"
#include "texture/footprint.h"

namespace lantern {
namespace {

// 100 x 100 pixels, 10 degrees across, at (0, 0, -10) looking down +z.
Camera narrow_camera() {
  CameraDesc d;
  d.world_from_camera = glm::translate(Mat4(1.f), Vec3(0, 0, -10));
  d.fov_degrees = 10.f;
  return Camera(d, 100, 100);
}

// A pixel step at distance 10 spans 2 tan(5 deg) * 10 / 100 on a plane
// facing the camera; with 64 samples per pixel each sample covers 1/8 of
// it. The camera's smallest differential (at the film's corner) is within
// 2% of the centre's at this field of view.
TEST(Footprint, PixelStepOnAPlaneFacingTheCamera) {
  FootprintModel fm(narrow_camera(), 64);
  Vec3 dpdx, dpdy;
  fm.dp_dxy(Vec3(0.f), Vec3(0, 0, -1), &dpdx, &dpdy);
  const float step = 2.f * std::tan(glm::radians(5.f)) * 10.f / 100.f / 8.f;
  EXPECT_NEAR(glm::length(dpdx), step, 0.02f * step);
  EXPECT_NEAR(glm::length(dpdy), step, 0.02f * step);
  EXPECT_NEAR(std::fabs(dpdx.x), glm::length(dpdx), 1e-3f * step) << "x steps along x";
  EXPECT_NEAR(std::fabs(dpdy.y), glm::length(dpdy), 1e-3f * step) << "y steps along y";
  // Off the axis the approximation turns the differential towards the point.
  fm.dp_dxy(Vec3(0.5f, 0.3f, 0.f), Vec3(0, 0, -1), &dpdx, &dpdy);
  EXPECT_NEAR(glm::length(dpdx), step, 0.03f * step);
  // 1 sample per pixel: the whole step; 1000: no less than 1/8 of it.
  FootprintModel one(narrow_camera(), 1), many(narrow_camera(), 1000);
  one.dp_dxy(Vec3(0.f), Vec3(0, 0, -1), &dpdx, &dpdy);
  EXPECT_NEAR(glm::length(dpdx), 8.f * step, 0.16f * step);
  many.dp_dxy(Vec3(0.f), Vec3(0, 0, -1), &dpdx, &dpdy);
  EXPECT_NEAR(glm::length(dpdx), step, 0.02f * step);
}

// A plane turned 60 degrees about y stretches the x step by 1/cos 60 = 2 and
// leaves the y step alone.
TEST(Footprint, TiltedPlaneStretchesTheStep) {
  FootprintModel fm(narrow_camera(), 64);
  Vec3 fx, fy, tx, ty;
  fm.dp_dxy(Vec3(0.f), Vec3(0, 0, -1), &fx, &fy);
  const float a = glm::radians(60.f);
  fm.dp_dxy(Vec3(0.f), Vec3(-std::sin(a), 0.f, -std::cos(a)), &tx, &ty);
  EXPECT_NEAR(glm::length(tx) / glm::length(fx), 2.f, 0.02f);
  EXPECT_NEAR(glm::length(ty) / glm::length(fy), 1.f, 0.02f);
  EXPECT_NEAR(glm::dot(tx, Vec3(-std::sin(a), 0.f, -std::cos(a))), 0.f, 1e-4f) << "in the plane";
}

// (u, v) derivatives by least squares: with u = 2 x, v = 4 y on the plane,
// du/dx is twice dx and dv/dy four times dy; a degenerate (u, v) gives 0.
TEST(Footprint, SurfaceCoordinateDerivatives) {
  FootprintModel fm(narrow_camera(), 64);
  Footprint f = fm.at(Vec3(0.f), Vec3(0, 0, -1), Vec3(0.5f, 0, 0), Vec3(0, 0.25f, 0));
  EXPECT_NEAR(f.duvdx.x, 2.f * f.dpdx.x, 1e-6f);
  EXPECT_NEAR(f.duvdx.y, 4.f * f.dpdx.y, 1e-6f);
  EXPECT_NEAR(f.duvdy.y, 4.f * f.dpdy.y, 1e-6f);
  Footprint d = fm.at(Vec3(0.f), Vec3(0, 0, -1), Vec3(0.f), Vec3(0.f));
  EXPECT_EQ(d.duvdx, Vec2(0.f));
  EXPECT_EQ(FootprintModel().at(Vec3(0.f), Vec3(0, 0, 1), Vec3(1, 0, 0), Vec3(0, 1, 0)).dpdx, Vec3(0.f))
      << "disabled: zero";
}

// A metal floor whose roughness is a fine checkerboard (filtered, it is a
// different, blurrier metal: the image depends on the footprint, not only
// on its mean) and a wall of a fine image read trilinearly and
// anisotropically, under a small light. The footprint is a function of the
// surface point, so every integrator shades a vertex alike and they
// converge to one image; and it does not depend on the thread count.
// The shading frame of a mesh with normals as pbrt-v4 builds it (ts = ns x
// dp/du, ss = ts x ns, neither normalised), and the parameterisation's own
// derivatives kept beside it for the footprint.
TEST(Footprint, MeshShadingFrameKeepsTheParameterisation) {
  TriangleMesh m;
  m.positions = {Vec3(-80, 0, -80), Vec3(80, 0, -80), Vec3(80, 0, 80), Vec3(0.f)};
  m.triangles = {glm::uvec3(0, 1, 2)};
  m.uvs = {Vec2(0, 0), Vec2(4, 0), Vec2(4, 1)};
  m.vertex_count = 3;
  SurfacePoint sp{Vec3(40, 0, 0), Vec3(0, 1, 0), Vec3(0, 1, 0), Vec2(3, 0.5f), 1.f};
  const ShadingGeometry plain = triangle_shading_geometry(m, 0, sp);
  EXPECT_FALSE(plain.turned);
  EXPECT_NEAR(glm::length(plain.dpdu - Vec3(40, 0, 0)), 0.f, 1e-4f);
  EXPECT_NEAR(glm::length(plain.dpdv - Vec3(0, 0, 160)), 0.f, 1e-4f);
  for (float side : {1.f, -1.f}) {
    m.normals.assign(3, Vec3(0, side, 0));
    sp.ns = sp.ng = Vec3(0, side, 0);
    const ShadingGeometry g = triangle_shading_geometry(m, 0, sp);
    EXPECT_TRUE(g.turned);
    EXPECT_NEAR(glm::length(g.uv_dpdu() - plain.dpdu), 0.f, 1e-4f) << side;
    EXPECT_NEAR(glm::length(g.uv_dpdv() - plain.dpdv), 0.f, 1e-4f) << side;
    EXPECT_NEAR(glm::length(g.dpdu - Vec3(40, 0, 0)), 0.f, 1e-3f) << side;
    EXPECT_NEAR(glm::length(g.dpdv - glm::cross(sp.ns, plain.dpdu)), 0.f, 1e-3f) << "|ts| = |dp/du|: " << side;
  }
}

// A checkerboard floor (checks 4 units wide on a 160-unit quad whose uv run
// 0..1) seen from 1 unit above, under a white sky at maxdepth 1: each near
// check's pixels are its reflectance, 0.9 or 0.1. Per-vertex normals, up
// or down as exporters write them, must not change the footprint. Mapped
// through unit shading tangents instead of dp/du and dp/dv (160 long), it
// spanned far too much of the texture: 0.88 and 0.13 here (measured).
TEST(Footprint, MeshNormalsLeaveTheFootprintAlone) {
  for (const char* normals : {"", "\"normal N\" [0 1 0 0 1 0 0 1 0 0 1 0]", "\"normal N\" [0 -1 0 0 -1 0 0 -1 0 0 -1 0]"}) {
    auto scene = load_scene_from_string(std::string(R"(LookAt 0 1 0  0 0.6 10  0 1 0
Camera "perspective" "float fov" 40
WorldBegin
LightSource "infinite" "rgb L" [1 1 1]
Texture "check" "spectrum" "checkerboard" "float uscale" 20 "float vscale" 20 "rgb tex1" [0.1 0.1 0.1] "rgb tex2" [0.9 0.9 0.9]
Material "diffuse" "texture reflectance" "check"
Shape "trianglemesh" "point3 P" [-80 0 -80  80 0 -80  80 0 80  -80 0 80] "point2 uv" [0 0 1 0 1 1 0 1]
      "integer indices" [0 1 2 0 2 3] )") + normals + "\n",
                                        "floor.pbrt", {});
    ASSERT_TRUE(scene->textures.uses_footprint);
    RenderOptions o;
    o.spp = 16;
    o.maxdepth = 1;
    o.width = 160;
    o.height = 120;
    const Image img = render(*scene, o).image;
    auto mean = [&](int x0, int y0, int x1, int y1) {
      double sum = 0.0;
      for (int y = y0; y < y1; ++y)
        for (int x = x0; x < x1; ++x) sum += img.at(x, y)[1];
      return sum / double((x1 - x0) * (y1 - y0));
    };
    EXPECT_NEAR(mean(10, 100, 60, 118), 0.9, 0.01) << "bright check, normals: " << normals;
    EXPECT_NEAR(mean(100, 100, 150, 118), 0.1, 0.01) << "dark check, normals: " << normals;
  }
}

TEST(Footprint, FilteredTexturesRenderAlikeWithEveryIntegrator) {
  auto dir = std::filesystem::temp_directory_path() / ("lantern-footprint-test-" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  const std::string image = (dir / "fine.exr").string();
  Image fine{512, 512, std::vector<float>(size_t(512) * 512 * 3)};
  for (int y = 0; y < 512; ++y)
    for (int x = 0; x < 512; ++x) {
      float* v = fine.at(x, y);
      v[0] = float((x ^ y) & 1);
      v[1] = float((x / 3 + y) & 1);
      v[2] = 0.5f;
    }
  write_image(image, fine, {});
  auto scene = load_scene_from_string(R"(LookAt 0 1 -3  0 0 2  0 1 0
Camera "perspective" "float fov" 50
WorldBegin
AttributeBegin
  AreaLightSource "diffuse" "rgb L" [8 8 8]
  Translate 0 2 1
  Shape "sphere" "float radius" 0.15
AttributeEnd
Texture "tri" "spectrum" "imagemap" "string filter" "trilinear" "float uscale" 4 "float vscale" 4 "string filename" ")" +
                                          image + R"("
Texture "ewa" "spectrum" "imagemap" "string filter" "ewa" "string filename" ")" + image + R"("
Texture "mixed" "spectrum" "checkerboard" "float uscale" 40 "float vscale" 40 "texture tex1" "tri" "texture tex2" "ewa"
Texture "rough" "float" "checkerboard" "float uscale" 60 "float vscale" 60 "float tex1" 0.02 "float tex2" 0.5
Material "conductor" "texture roughness" "rough" "spectrum eta" "metal-Cu-eta" "spectrum k" "metal-Cu-k"
Shape "bilinearmesh" "point3 P" [-4 0 -2  4 0 -2  -4 0 8  4 0 8]
Material "diffuse" "texture reflectance" "mixed"
Shape "bilinearmesh" "point3 P" [-4 0 8  4 0 8  -4 4 8  4 4 8]
)",
                                      "footprint.pbrt", {});
  ASSERT_TRUE(scene->textures.uses_footprint);
  const int w = 16, h = 12;
  const std::vector<Region> regions = {{0, 0, w, h}, {0, 8, 8, 4}, {8, 8, 8, 4}, {4, 4, 8, 4}};
  auto path = render_stats(*scene, "path", w, h, 64, 12, regions);
  auto bdpt = render_stats(*scene, "bdpt", w, h, 16, 12, regions);
  auto lt = render_stats(*scene, "lt", w, h, 32, 12, regions);
  EXPECT_LT(max_z(bdpt, path), 4.5);
  EXPECT_LT(max_z(lt, path), 4.5);
  RenderOptions o;
  o.spp = 2;
  o.width = 32;
  o.height = 24;
  expect_thread_invariant(*scene, o, {"path", "bdpt"});
  std::error_code ec;
  std::filesystem::remove_all(dir, ec);
}

}  // namespace
}  // namespace lantern
