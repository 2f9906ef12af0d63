// pbrt-v3's "nurbs" and "heightfield" shapes (geometry/nurbs.h,
// scene/builder_v3_shapes.cpp): the surface against closed forms (a
// bilinear patch, a rational circle), its derivatives against finite
// differences, the meshes against the trianglemesh pbrt-v4's upgrade
// writes for them, and clear errors for bad numbers.
#include <gtest/gtest.h>

#include <cmath>
#include <sstream>

#include "expect_error.h"
#include "geometry/nurbs.h"
#include "lantern/render.h"
#include "lantern/scene.h"

namespace lantern {
namespace {

NurbsSurface bilinear(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
  NurbsSurface s;
  s.nu = s.nv = 2;
  s.uorder = s.vorder = 2;
  s.uknots = s.vknots = {0.f, 0.f, 1.f, 1.f};
  s.points = {glm::vec4(a, 1.f), glm::vec4(b, 1.f), glm::vec4(c, 1.f), glm::vec4(d, 1.f)};
  s.u0 = s.v0 = 0.f;
  s.u1 = s.v1 = 1.f;
  return s;
}

// The unit circle as nine rational quadratic control points (weights 1 and
// 1/sqrt(2) at the square's corners; The NURBS Book, ex. 7.2), swept from z
// = 0 to z = 2: a cylinder of radius 1.
NurbsSurface cylinder() {
  const float h = std::sqrt(0.5f);
  const float xy[9][2] = {{1, 0}, {1, 1}, {0, 1}, {-1, 1}, {-1, 0}, {-1, -1}, {0, -1}, {1, -1}, {1, 0}};
  NurbsSurface s;
  s.nu = 9, s.nv = 2, s.uorder = 3, s.vorder = 2;
  s.uknots = {0, 0, 0, 0.25f, 0.25f, 0.5f, 0.5f, 0.75f, 0.75f, 1, 1, 1};
  s.vknots = {0, 0, 1, 1};
  for (float z : {0.f, 2.f})
    for (int i = 0; i < 9; ++i) {
      const float w = i % 2 ? h : 1.f;
      s.points.emplace_back(w * xy[i][0], w * xy[i][1], w * z, w);
    }
  s.u0 = s.v0 = 0.f;
  s.u1 = s.v1 = 1.f;
  return s;
}

TEST(Nurbs, OrderTwoIsTheBilinearPatch) {
  const Vec3 a(0, 0, 0), b(2, 0, 1), c(0, 1, 0.5f), d(3, 2, -1);
  const NurbsSurface s = bilinear(a, b, c, d);
  ASSERT_EQ(nurbs_problem(s), "");
  for (float u : {0.f, 0.3f, 1.f})
    for (float v : {0.f, 0.6f, 1.f}) {
      const NurbsPoint e = evaluate_nurbs(s, u, v);
      const Vec3 want = glm::mix(glm::mix(a, b, u), glm::mix(c, d, u), v);
      EXPECT_LT(glm::length(e.p - want), 1e-6f) << u << " " << v;
      EXPECT_LT(glm::length(e.dpdu - glm::mix(b - a, d - c, v)), 1e-5f);
      EXPECT_LT(glm::length(e.dpdv - glm::mix(c - a, d - b, u)), 1e-5f);
    }
}

TEST(Nurbs, ARationalCylinderKeepsItsRadiusAndFacesOutwards) {
  const NurbsSurface s = cylinder();
  ASSERT_EQ(nurbs_problem(s), "");
  const TriangleMesh m = tessellate_nurbs(s);
  ASSERT_EQ(m.positions.size(), 900u);
  EXPECT_EQ(m.triangles.size(), 2u * 29u * 29u);  // pbrt-v3's 30 x 30 dicing
  for (size_t i = 0; i < m.positions.size(); ++i) {
    const Vec3 p = m.positions[i];
    EXPECT_NEAR(std::hypot(p.x, p.y), 1.f, 2e-6f) << i;
    // cross(dpdu, dpdv): the circle runs counter-clockwise and v up, so
    // the normal is the outward radius.
    EXPECT_GT(glm::dot(m.normals[i], Vec3(p.x, p.y, 0.f)), 0.9999f) << i;
    EXPECT_NEAR(p.z, 2.f * m.uvs[i].y, 1e-6f);
  }
  // A quarter of it, by its parameter range.
  NurbsSurface q = s;
  q.u1 = 0.25f;
  const TriangleMesh mq = tessellate_nurbs(q);
  for (const Vec3& p : mq.positions) EXPECT_TRUE(p.x >= -1e-6f && p.y >= -1e-6f) << p.x << " " << p.y;
}

// Knots repeated past the order at the end leave an empty last span: the
// end of the range is evaluated on the last span that is not (it was 0/0).
TEST(Nurbs, RepeatedEndKnotsKeepTheEndOfTheRange) {
  NurbsSurface s = bilinear(Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(1, 1, 1));
  s.nu = 3;
  s.uknots = {0, 0, 1, 1, 1};
  s.points = {glm::vec4(0, 0, 0, 1), glm::vec4(1, 0, 0, 1), glm::vec4(9, 9, 9, 1),
              glm::vec4(0, 1, 0, 1), glm::vec4(1, 1, 1, 1), glm::vec4(9, 9, 9, 1)};
  s.u1 = s.uknots[size_t(s.nu)];
  ASSERT_EQ(nurbs_problem(s), "");
  const NurbsPoint e = evaluate_nurbs(s, 1.0, 0.5);
  EXPECT_LT(glm::length(e.p - Vec3(1.f, 0.5f, 0.5f)), 1e-6f) << e.p.x << " " << e.p.y << " " << e.p.z;
  for (const Vec3& p : tessellate_nurbs(s).positions) EXPECT_TRUE(std::isfinite(p.x + p.y + p.z));
}

TEST(Nurbs, DerivativesMatchFiniteDifferences) {
  // A non-uniform cubic by quadratic surface with uneven weights.
  NurbsSurface s;
  s.nu = 6, s.nv = 4, s.uorder = 4, s.vorder = 3;
  s.uknots = {0, 0, 0, 0, 0.3f, 0.7f, 1, 1, 1, 1};
  s.vknots = {0, 0, 0, 0.4f, 1, 1, 1};
  for (int j = 0; j < s.nv; ++j)
    for (int i = 0; i < s.nu; ++i) {
      const float w = 0.5f + 0.1f * float((i * 7 + j * 3) % 10);
      s.points.emplace_back(w * float(i), w * float(j), w * std::sin(float(i + 2 * j)), w);
    }
  s.u1 = s.v1 = 1.f;
  ASSERT_EQ(nurbs_problem(s), "");
  const double h = 1e-4;
  for (double u : {0.05, 0.3, 0.5, 0.95})
    for (double v : {0.1, 0.4, 0.8}) {
      const NurbsPoint e = evaluate_nurbs(s, u, v);
      const Vec3 du = (evaluate_nurbs(s, u + h, v).p - evaluate_nurbs(s, u - h, v).p) / float(2 * h);
      const Vec3 dv = (evaluate_nurbs(s, u, v + h).p - evaluate_nurbs(s, u, v - h).p) / float(2 * h);
      EXPECT_LT(glm::length(e.dpdu - du), 2e-3f * std::max(1.f, glm::length(du))) << u << " " << v;
      EXPECT_LT(glm::length(e.dpdv - dv), 2e-3f * std::max(1.f, glm::length(dv))) << u << " " << v;
    }
}

std::string scene_with(const std::string& shape) {
  return "LookAt 0.5 -1.5 2  0.5 0.5 0  0 0 1\nCamera \"perspective\" \"float fov\" 45\n"
         "Film \"rgb\" \"integer xresolution\" 24 \"integer yresolution\" 16\nSampler \"halton\"\n"
         "WorldBegin\nLightSource \"infinite\" \"rgb L\" [0.8 0.9 1]\n"
         "Texture \"checks\" \"spectrum\" \"checkerboard\" \"float uscale\" 4 \"float vscale\" 4 "
         "\"rgb tex1\" [0.8 0.2 0.1] \"rgb tex2\" [0.1 0.3 0.7]\n"
         "Material \"diffuse\" \"texture reflectance\" \"checks\"\n" + shape + "\n";
}

// A heightfield is the trianglemesh of its grid (pbrt-v3 makes it so, and
// pbrt-v4's upgrade writes that mesh out): the same image, bit for bit.
TEST(Heightfield, IsTheTrianglemeshOfItsGrid) {
  // (Grid steps of 1/4 and 1/2, exact in decimal and binary alike.)
  const float z[15] = {0, 0.2f, 0.1f, 0.3f, 0.4f, 0.6f, 0.2f, 0.1f, 0.5f, 0.3f, 0.9f, 0.2f, 0.4f, 0.1f, 0.3f};
  std::ostringstream pz, P, uv, idx;
  for (int j = 0; j < 3; ++j)
    for (int i = 0; i < 5; ++i) {
      pz << z[j * 5 + i] << " ";
      P << float(i) / 4.f << " " << float(j) / 2.f << " " << z[j * 5 + i] << " ";
      uv << float(i) / 4.f << " " << float(j) / 2.f << " ";
    }
  for (int j = 0; j < 2; ++j)
    for (int i = 0; i < 4; ++i) {
      const int a = j * 5 + i;
      idx << a << " " << a + 1 << " " << a + 6 << " " << a << " " << a + 6 << " " << a + 5 << " ";
    }
  auto field = load_scene_from_string(
      scene_with("Shape \"heightfield\" \"integer nu\" 5 \"integer nv\" 3 \"float Pz\" [" + pz.str() + "]"), "hf.pbrt", {});
  auto mesh = load_scene_from_string(scene_with("Shape \"trianglemesh\" \"point3 P\" [" + P.str() + "] \"point2 uv\" [" +
                                                uv.str() + "] \"integer indices\" [" + idx.str() + "]"),
                                     "mesh.pbrt", {});
  EXPECT_EQ(scene_info(*field).triangles, 16u);
  RenderOptions o;
  o.spp = 4;
  const Image a = render(*field, o).image, b = render(*mesh, o).image;
  ASSERT_EQ(a.rgb.size(), b.rgb.size());
  EXPECT_EQ(a.rgb, b.rgb);
  double sum = 0.0;
  for (float x : a.rgb) sum += x;
  EXPECT_GT(sum, 0.0);  // the field is in view
}

// A nurbs shape loads as its 30 x 30 dicing, renders in view, and has the
// transform and orientation of any shape.
TEST(Nurbs, LoadsAsItsDicing) {
  auto s = load_scene_from_string(
      scene_with("Shape \"nurbs\" \"integer nu\" 2 \"integer nv\" 2 \"integer uorder\" 2 \"integer vorder\" 2 "
                 "\"float uknots\" [0 0 1 1] \"float vknots\" [0 0 1 1] \"float Pw\" [0 0 0 1  1 0 0 1  0 1 0 1  1 1 0.5 1]"),
      "nurbs.pbrt", {});
  EXPECT_EQ(scene_info(*s).triangles, 2u * 29u * 29u);
  RenderOptions o;
  o.spp = 1;
  double sum = 0.0;
  for (float x : render(*s, o).image.rgb) sum += x;
  EXPECT_GT(sum, 0.0);
}

TEST(Nurbs, BadNumbersGiveClearErrors) {
  const std::string head = "WorldBegin\nShape \"nurbs\" \"integer nu\" 2 \"integer nv\" 2 \"integer uorder\" 2 "
                           "\"integer vorder\" 2 ";
  const std::string P = " \"point3 P\" [0 0 0 1 0 0 0 1 0 1 1 0]";
  expect_load_error(head + "\"float uknots\" [0 0 1] \"float vknots\" [0 0 1 1]" + P, "count.pbrt",
                    {"count.pbrt:2", "\"uknots\" has 3 values", "expected nu + uorder = 4"});
  expect_load_error(head + "\"float uknots\" [0 1 0.5 1] \"float vknots\" [0 0 1 1]" + P, "order.pbrt",
                    {"order.pbrt:2", "non-decreasing"});
  expect_load_error(head + "\"float uknots\" [0 0 1 1] \"float vknots\" [0 0 1 1] \"float u1\" 2" + P, "range.pbrt",
                    {"range.pbrt:2", "within the knots' range"});
  expect_load_error(head + "\"float uknots\" [0 0 1 1] \"float vknots\" [0 0 1 1] \"float Pw\" [0 0 0 1 1 0 0]",
                    "pw.pbrt", {"pw.pbrt:2", "four values"});
  expect_load_error(head + "\"float uknots\" [0 0 1 1] \"float vknots\" [0 0 1 1] \"point3 P\" [0 0 0 1 0 0 0 1 0]",
                    "points.pbrt", {"points.pbrt:2", "expected nu x nv = 4 control points, given 3"});
  expect_load_error("WorldBegin\nShape \"nurbs\" \"integer nu\" 2" + P, "missing.pbrt",
                    {"missing.pbrt:2", "needs \"nv\""});
  expect_load_error("WorldBegin\nShape \"heightfield\" \"integer nu\" 2 \"integer nv\" 2 \"float Pz\" [0 0 0]",
                    "hf.pbrt", {"hf.pbrt:2", "\"float Pz\" has 3 values, expected nu x nv = 4"});
  expect_load_error("WorldBegin\nShape \"heightfield\" \"integer nu\" 1 \"integer nv\" 2 \"float Pz\" [0 0]",
                    "hf1.pbrt", {"hf1.pbrt:2", "2 or more"});
}

}  // namespace
}  // namespace lantern
