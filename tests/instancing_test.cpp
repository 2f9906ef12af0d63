// Object instancing: a scene of instances and the same scene with every
// instance written out as plain shapes must render the same image, with
// the path tracer and with bdpt, whether Embree's instances (the fast
// memory layout) or the compact user geometry place them; and misuse gets
// a clear error.
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

// A little sculpture: a glossy wedge (no normals), a smooth-shaded quad
// (with normals and uvs), a cylinder (a quadric: user geometry inside the
// instance) and a glass sphere.
const char* const kObjectBody = R"(
  AttributeBegin
    Material "conductor" "float roughness" [ 0.25 ]
    Shape "trianglemesh" "point3 P" [ 0 0 0  1 0 0  0 1 0  0 0 1 ] "integer indices" [ 0 2 1  0 1 3  0 3 2  1 2 3 ]
  AttributeEnd
  AttributeBegin
    Material "diffuse" "rgb reflectance" [ 0.7 0.3 0.2 ]
    Translate 0 -0.01 0
    Shape "trianglemesh" "point3 P" [ -1 0 -1  1 0 -1  1 0 1  -1 0 1 ] "integer indices" [ 0 2 1  0 3 2 ]
      "normal N" [ -0.3 1 -0.3  0.3 1 -0.3  0.3 1 0.3  -0.3 1 0.3 ] "point2 uv" [ 0 0  1 0  1 1  0 1 ]
  AttributeEnd
  AttributeBegin
    Material "diffuse" "rgb reflectance" [ 0.2 0.5 0.6 ]
    Translate 0.6 0 -0.5  Rotate -90 1 0 0
    Shape "cylinder" "float radius" [ 0.15 ] "float zmax" [ 0.8 ]
  AttributeEnd
  AttributeBegin
    Material "dielectric" "float eta" [ 1.5 ]
    Translate -0.5 0.3 0.4
    Shape "sphere" "float radius" [ 0.3 ]
  AttributeEnd
)";

// Placements: rotation, translation, uniform and non-uniform scale, and a
// mirror image. Spheres stay spheres only under uniform scale, so the
// non-uniform and mirrored placements use a sphere-free object.
struct TestPlacement {
  std::string transform;
  bool uniform;
};
const std::vector<TestPlacement> kPlacements = {
    {"Translate -1.2 0 0  Rotate 30 0 1 0", true},
    {"Translate 1.1 0.2 -0.3  Rotate -70 0 1 0  Scale 0.6 0.6 0.6", true},
    {"Translate 0 0 -1.5  Rotate 15 1 0 0  Scale 1.4 0.5 0.8", false},
    {"Translate 0.4 0 1.2  Scale -0.7 0.7 0.7", false},
};

std::string instancing_scene_text(bool instanced) {
  std::ostringstream t;
  // World space: the test traces rays given in world coordinates.
  t << "Option \"string renderingcoordinatesystem\" \"world\"\nLookAt 0 3 5  0 0 0  0 1 0\nCamera \"perspective\" \"float fov\" [ 45 ]\nWorldBegin\n"
    << "LightSource \"infinite\" \"rgb L\" [ 0.2 0.22 0.25 ]\n"
    << "AttributeBegin\n AreaLightSource \"diffuse\" \"rgb L\" [ 12 11 9 ]\n Translate 1 3 1\n"
    << " Shape \"sphere\" \"float radius\" [ 0.3 ]\nAttributeEnd\n"
    << "Shape \"trianglemesh\" \"point3 P\" [ -6 -0.02 -6  6 -0.02 -6  6 -0.02 6  -6 -0.02 6 ] \"integer indices\" [ 0 2 1 0 3 2 ]\n";
  const std::string no_sphere = std::string(kObjectBody).substr(0, std::string(kObjectBody).rfind("  AttributeBegin"));
  if (instanced) {
    t << "ObjectBegin \"sculpture\"\n" << kObjectBody << "ObjectEnd\n";
    t << "ObjectBegin \"wedges\"\n" << no_sphere << "ObjectEnd\n";
  }
  for (const TestPlacement& p : kPlacements) {
    t << "AttributeBegin\n  " << p.transform << "\n";
    if (instanced) t << "  ObjectInstance \"" << (p.uniform ? "sculpture" : "wedges") << "\"\n";
    else t << (p.uniform ? std::string(kObjectBody) : no_sphere);
    t << "AttributeEnd\n";
  }
  return t.str();
}

// The same rays into both scenes: every hit must be the same surface point,
// with the same normals, uv and kind of material, whichever of Embree's
// back ends traced it.
std::shared_ptr<Scene> load_instanced(MemoryLayout layout) {
  LoadOptions lo;
  lo.memory_layout = layout;
  auto scene = load_scene_from_string(instancing_scene_text(true), "instanced.pbrt", lo);
  EXPECT_EQ(scene->accel->compact_instances(), layout == MemoryLayout::Compact);
  return scene;
}

TEST(Instancing, HitsMatchTheFlattenedGeometry) {
  auto flat = load_scene_from_string(instancing_scene_text(false), "flat.pbrt");
  for (MemoryLayout layout : {MemoryLayout::Fast, MemoryLayout::Compact})
  for (const char* backend : {"stream", "single", "packet16"}) {
    SCOPED_TRACE(std::string(backend) + " " + name(layout));
    auto instanced = load_instanced(layout);
    RayBatch a, b;
    RandomStream s = RandomStream::make(9, 0, 0);
    for (int i = 0; i < 20000; ++i) {
      Vec3 o(6.f * s.get1d() - 3.f, 3.f * s.get1d(), 6.f * s.get1d() - 3.f);
      Vec3 target(4.f * s.get1d() - 2.f, 1.2f * s.get1d() - 0.1f, 4.f * s.get1d() - 2.f);
      a.push(o, target - o, 0.f, 1e30f, 0.f);
      b.push(o, target - o, 0.f, 1e30f, 0.f);
    }
    RayStream ia(instanced->accel->handle(), parse_ray_backend(backend), nullptr);
    ia.set_scene(instanced->accel->instance_base(), &instanced->shapes);
    ia.intersect(a, RayKind::Extension);
    RayStream(flat->accel->handle(), parse_ray_backend(backend), nullptr).intersect(b, RayKind::Extension);
    int compared = 0, instanced_hits = 0, disagree = 0;
    for (uint32_t i = 0; i < a.count; ++i) {
      if (a.hit(i) != b.hit(i) || std::fabs(a.tfar[i] - b.tfar[i]) > 1e-3f * b.tfar[i]) {
        ++disagree;  // grazing an edge: rounding may decide either way
        continue;
      }
      if (!a.hit(i)) continue;
      ++compared;
      instanced_hits += a.inst_id[i] != kInvalidGeometry;
      SurfacePoint pa = hit_point(instanced->shapes, a, i), pb = hit_point(flat->shapes, b, i);
      ASSERT_LT(glm::length(pa.p - pb.p), 1e-4f) << "ray " << i;
      // As in pbrt-v4, a quadric's normal flips under a shape transform that
      // swaps handedness (the mirrored placement, written out flat), not
      // under an instance's: the same surface, the other side called outside.
      const bool quadric = flat->shapes.geometries[b.geom_id[i]].kind == ShapeKind::Quadric;
      const float sign = quadric && glm::dot(pa.ng, pb.ng) < 0.f ? -1.f : 1.f;
      ASSERT_GT(sign * glm::dot(pa.ng, pb.ng), 0.9999f) << "ray " << i;
      ASSERT_GT(sign * glm::dot(pa.ns, pb.ns), 0.9999f) << "ray " << i;
      ASSERT_LT(glm::length(pa.uv - pb.uv), 1e-4f) << "ray " << i;
      ASSERT_EQ(instanced->shapes.geometries[a.geom_id[i]].material.kind(), flat->shapes.geometries[b.geom_id[i]].material.kind());
    }
    EXPECT_GT(instanced_hits, 2000);
    EXPECT_LT(disagree, a.count / 500);
    EXPECT_GT(compared, 5000);
  }
}

TEST(Instancing, InstancedAndFlattenedScenesRenderTheSameImage) {
  auto instanced = load_instanced(MemoryLayout::Fast), compact = load_instanced(MemoryLayout::Compact);
  auto flat = load_scene_from_string(instancing_scene_text(false), "flat.pbrt");
  SceneInfo a = scene_info(*instanced), b = scene_info(*flat);
  EXPECT_EQ(a.instances, 4u);
  EXPECT_EQ(a.instanced_triangles, b.triangles);
  EXPECT_LT(a.triangles, b.triangles);
  const std::vector<Region> regions = {{0, 0, 32, 24}, {0, 0, 16, 12}, {16, 0, 16, 12}, {0, 12, 16, 12}, {16, 12, 16, 12}};
  for (const char* integrator : {"path", "bdpt"}) {
    SCOPED_TRACE(integrator);
    RenderOptions o;
    o.integrator = parse_integrator(integrator);
    o.width = 32;
    o.height = 24;
    o.spp = 8;
    o.maxdepth = 6;
    auto si = stats_of(render_runs(*instanced, o, 10, 1), regions);
    auto sc = stats_of(render_runs(*compact, o, 10, 1), regions);
    auto sf = stats_of(render_runs(*flat, o, 10, 1), regions);
    EXPECT_GT(sf.mean[0][0], 0.01);
    EXPECT_LT(max_z(si, sf), 5.0);
    EXPECT_LT(max_z(sc, sf), 5.0);
  }
}

// An object whose only shape turns out empty (a PLY of no faces, read
// after its placements) has no bounds: the compact layout must leave its
// instances out, as Embree's instances of an empty scene are.
TEST(Instancing, EmptyObjectsPlacedCompactlyTraceNothing) {
  const auto ply = std::filesystem::temp_directory_path() / "lantern-empty-object.ply";
  std::ofstream(ply) << "ply\nformat ascii 1.0\nelement vertex 0\nproperty float x\nproperty float y\nproperty float z\n"
                        "element face 0\nproperty list uchar int vertex_indices\nend_header\n";
  const std::string text = "LookAt 0 0 -5 0 0 0 0 1 0\nCamera \"perspective\"\n"
                           "Film \"rgb\" \"integer xresolution\" [ 16 ] \"integer yresolution\" [ 16 ]\nWorldBegin\n"
                           "LightSource \"infinite\" \"rgb L\" [ 1 1 1 ]\n"
                           "ObjectBegin \"empty\"\nShape \"plymesh\" \"string filename\" \"" + ply.string() + "\"\nObjectEnd\n"
                           "ObjectBegin \"ball\"\nShape \"sphere\"\nObjectEnd\n"
                           "ObjectInstance \"empty\"\nTranslate 1 0 0\nObjectInstance \"empty\"\nObjectInstance \"ball\"\n";
  LoadOptions fast, compact;
  fast.memory_layout = MemoryLayout::Fast;
  compact.memory_layout = MemoryLayout::Compact;
  fast.warn = compact.warn = [](const std::string&) {};
  auto a = load_scene_from_string(text, "fast.pbrt", fast), b = load_scene_from_string(text, "compact.pbrt", compact);
  ASSERT_TRUE(b->accel->compact_instances());
  expect_identical_renders(*a, *b, {"path"});
}

std::string instancing_load_error(const std::string& text) {
  try {
    load_scene_from_string(text, "t.pbrt");
  } catch (const InputError& e) {
    return e.what();
  }
  return "(no error)";
}

TEST(Instancing, MisuseGetsClearErrors) {
  const std::string w = "WorldBegin\n";
  EXPECT_NE(instancing_load_error(w + "ObjectBegin \"a\"\nAreaLightSource \"diffuse\"\nShape \"sphere\"\nObjectEnd\n")
                .find("area lights inside ObjectBegin/ObjectEnd are not supported"),
            std::string::npos);
  EXPECT_NE(instancing_load_error(w + "ObjectBegin \"a\"\nObjectBegin \"b\"\n").find("t.pbrt:3:1: error: ObjectBegin \"b\" inside"),
            std::string::npos);
  EXPECT_NE(instancing_load_error(w + "ObjectBegin \"a\"\nShape \"sphere\"\nObjectEnd\nObjectBegin \"b\"\nObjectInstance \"a\"\n")
                .find("nested instancing is not supported"),
            std::string::npos);
  EXPECT_NE(instancing_load_error(w + "ObjectInstance \"nope\"\n").find("t.pbrt:2:1: error: ObjectInstance \"nope\": no object"),
            std::string::npos);
  EXPECT_NE(instancing_load_error(w + "ObjectEnd\n").find("ObjectEnd without ObjectBegin"), std::string::npos);
  EXPECT_NE(instancing_load_error(w + "ObjectBegin \"a\"\nAttributeBegin\nObjectEnd\n").find("does not close"), std::string::npos);
  EXPECT_NE(instancing_load_error(w + "ObjectBegin \"a\"\nAttributeEnd\n").find("would close an ObjectBegin"), std::string::npos);
  EXPECT_NE(instancing_load_error(w + "ObjectBegin \"a\"\nObjectEnd\nObjectBegin \"a\"\nObjectEnd\n").find("defined twice"),
            std::string::npos);
  EXPECT_NE(instancing_load_error(w + "ObjectBegin \"a\"\nShape \"sphere\"\nObjectEnd\nScale 0 1 1\nObjectInstance \"a\"\n").find("singular"),
            std::string::npos);
  // An object that is never closed, or an empty one instanced: fine or clear.
  EXPECT_NE(instancing_load_error(w + "ObjectBegin \"a\"\nShape \"sphere\"\n").find("t.pbrt:2:1"), std::string::npos);
  EXPECT_EQ(instancing_load_error(w + "ObjectBegin \"empty\"\nObjectEnd\nObjectInstance \"empty\"\n"), "(no error)");
}

}  // namespace
}  // namespace lantern
