// Bump and normal maps: path, bdpt and light tracing agree on a scene with a
// strong bump map and a normal map under a small light (the shading normals
// they make go through the shading-normal corrections of light transport);
// a flat normal map gives the image without one; a tilted one turns the
// shading normal the way pbrt-v4's tangent space says.
#include <gtest/gtest.h>

#include <filesystem>

#include "accel/ray_stream.h"
#include "integrator/hit_material.h"
#include "stat_compare.h"

namespace lantern {
namespace {

std::string normal_map_file(const char* name, Vec3 n) {
  auto dir = std::filesystem::temp_directory_path() / ("lantern-bump-test-" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  std::string path = (dir / name).string();
  Vec3 c = 0.5f * (glm::normalize(n) + Vec3(1.f));
  // A 4x4 map: one tilt, or the tilt and its mirror image in checks.
  Image img{4, 4, {}};
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < 4; ++x) {
      Vec3 v = ((x + y) & 1) && glm::normalize(n).z < 0.99f ? Vec3(1.f - c.x, 1.f - c.y, c.z) : c;
      img.rgb.insert(img.rgb.end(), {v.x, v.y, v.z});
    }
  write_image(path, img, {});
  return path;
}

std::string bump_scene_text(const std::string& floor_material, const std::string& sphere_material) {
  return R"(
LookAt 0 3 -3  0 0.3 0  0 1 0
Camera "perspective" "float fov" [ 30 ]
Film "rgb" "integer xresolution" [ 24 ] "integer yresolution" [ 24 ]
PixelFilter "gaussian"
WorldBegin
AttributeBegin
  AreaLightSource "diffuse" "rgb L" [ 40 40 40 ]
  Translate -1 2.5 0.5
  Shape "sphere" "float radius" [ 0.08 ]
AttributeEnd
)" + floor_material + R"(
Shape "trianglemesh" "point3 P" [ -3 0 -3  3 0 -3  3 0 3  -3 0 3 ] "integer indices" [ 0 1 2  0 2 3 ]
  "point2 uv" [ 0 0  4 0  4 4  0 4 ]
)" + sphere_material + R"(
Translate 0.3 0.5 0.3
Shape "sphere" "float radius" [ 0.5 ]
)";
}

TEST(Bump, PathBdptAndLightTracingAgree) {
  std::string map = normal_map_file("tilted.exr", Vec3(0.6f, 0.2f, 0.77f));
  auto scene = load_scene_from_string(
      bump_scene_text(R"(Material "diffuse" "rgb reflectance" [ 0.6 0.6 0.6 ] "string normalmap" ")" + map + "\"",
                 R"(Texture "bumps" "float" "wrinkled" "integer octaves" [ 3 ]
Texture "bumpscale" "float" "scale" "texture tex" "bumps" "float scale" [ 0.05 ]
Material "coateddiffuse" "rgb reflectance" [ 0.5 0.3 0.2 ] "float roughness" [ 0.1 ] "texture displacement" "bumpscale")"),
      "bump.pbrt");
  const std::vector<Region> regions = {{0, 0, 24, 24}, {0, 0, 8, 8}, {8, 8, 8, 8}, {16, 8, 8, 8}, {0, 16, 8, 8}};
  auto path = render_stats(*scene, "path", 24, 24, 64, 12, regions);
  auto bdpt = render_stats(*scene, "bdpt", 24, 24, 16, 12, regions);
  auto lt = render_stats(*scene, "lt", 24, 24, 32, 12, regions);
  EXPECT_LT(max_z(bdpt, path), 4.5);
  EXPECT_LT(max_z(lt, path), 4.5);
}

TEST(Bump, FlatNormalMapChangesNothing) {
  std::string flat = normal_map_file("flat.exr", Vec3(0, 0, 1));
  auto plain = load_scene_from_string(bump_scene_text(R"(Material "diffuse" "rgb reflectance" [ 0.6 0.6 0.6 ])",
                                                 R"(Material "diffuse" "rgb reflectance" [ 0.5 0.3 0.2 ])"),
                                      "plain.pbrt");
  auto mapped = load_scene_from_string(
      bump_scene_text(R"(Material "diffuse" "rgb reflectance" [ 0.6 0.6 0.6 ] "string normalmap" ")" + flat + "\"",
                 R"(Material "diffuse" "rgb reflectance" [ 0.5 0.3 0.2 ] "string normalmap" ")" + flat + "\""),
      "flat.pbrt");
  RenderOptions o;
  o.spp = 8;
  for (const char* integrator : {"path", "bdpt"}) {
    o.integrator = parse_integrator(integrator);
    Image a = render(*plain, o).image, b = render(*mapped, o).image;
    double sa = 0, sb = 0, diff = 0;
    for (size_t k = 0; k < a.rgb.size(); ++k) {
      sa += a.rgb[k];
      sb += b.rgb[k];
      diff = std::max(diff, double(std::fabs(a.rgb[k] - b.rgb[k])));
    }
    // The normals differ only by rounding: the same paths, nearly the same sums.
    EXPECT_NEAR(sb / sa, 1.0, 1e-4) << integrator;
  }
}

// A normal map tilted towards +u (x in tangent space) turns the floor's
// shading normal towards +dp/du, which is +x on this floor; in the map's
// mirrored checks, towards -x. Rays straight down at texel centres.
TEST(Bump, NormalMapTangentSpace) {
  std::string map = normal_map_file("plus-u.exr", Vec3(1.f, 0.f, 1.f));
  auto scene = load_scene_from_string(
      "Option \"string renderingcoordinatesystem\" \"world\"\n" + bump_scene_text(R"(Material "diffuse" "string normalmap" ")" + map + "\"", ""),
      "tangent.pbrt");  // world space: the ray below is given in world coordinates
  const Scene& s = *scene;
  RayCounters counters;
  RayStream stream(s.accel->handle(), RayBackend::Single, &counters);
  // u = 4 (x + 3) / 6: x = 0.1875 is u = 2.125 (texel column 0), 0.5625 is
  // u = 2.375 (column 1); z = -1.3125 is v = 1.125, image row 3 (t = 1 - v),
  // away from the sphere.
  // Texel (column + row) odd holds the mirrored tilt.
  struct Probe {
    float x, expected_sign;
  } probes[] = {{0.1875f, -1.f}, {0.5625f, 1.f}};
  for (const Probe& p : probes) {
    RayBatch rays;
    rays.push(Vec3(p.x, 1.f, -1.3125f), Vec3(0, -1, 0), 0.f, kInfinity, 0.f);
    stream.intersect(rays, RayKind::Camera);
    ASSERT_TRUE(rays.hit(0));
    SurfacePoint sp = hit_point(s.shapes, rays, 0);
    Footprint fp;
    hit_material(s, FootprintModel(), rays, 0, Vec3(0, -1, 0), &sp, &fp);
    EXPECT_NEAR(sp.ns.x, p.expected_sign * std::sqrt(0.5f), 1e-3f) << "x " << p.x;
    EXPECT_NEAR(std::fabs(sp.ns.y), std::sqrt(0.5f), 1e-3f);
    EXPECT_NEAR(sp.ns.z, 0.f, 1e-3f);
  }
}

}  // namespace
}  // namespace lantern
