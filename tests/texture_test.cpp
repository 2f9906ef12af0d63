// Texture classes against closed forms, image orientation, wrap modes and
// encodings on small known images, texture parameters of materials, and the
// errors for misused textures.
#include <gtest/gtest.h>

#include <filesystem>

#include "expect_error.h"
#include "geometry/bilinear_patch.h"
#include "geometry/surface.h"
#include "lantern/image.h"
#include "lantern/render.h"
#include "material/bsdf_kernel.h"
#include "math/rng.h"
#include "scene/scene.h"
#include "stat_compare.h"
#include "texture/noise.h"

namespace lantern {
namespace {

std::shared_ptr<Scene> load_texture_scene(const std::string& text) { return load_scene_from_string(text, "t.pbrt", {}); }

// The scene's float or spectrum texture bound to material parameter
// "reflectance" of its only diffuse material.
const RGBTextureRef& diffuse_reflectance(const Scene& s) { return s.materials.diffuse.at(0).reflectance; }

RGB eval(const Scene& s, const RGBTextureRef& t, Vec2 uv, Vec3 p = Vec3(0.f), Vec3 n = Vec3(0, 0, 1)) {
  return s.textures.evaluate(t, TextureContext{p, n, uv});
}
float eval_float(const Scene& s, const FloatTextureRef& t, Vec2 uv) {
  return s.textures.evaluate_float(t, TextureContext{Vec3(0.f), Vec3(0, 0, 1), uv});
}

std::string tmp_path(const std::string& name) {
  auto dir = std::filesystem::temp_directory_path() / ("lantern-texture-test-" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  return (dir / name).string();
}

TEST(Texture, CheckerboardMeanOverWholePeriodsAndParity) {
  auto s = load_texture_scene(R"(WorldBegin
Texture "c" "spectrum" "checkerboard" "rgb tex1" [0.2 0.2 0.2] "rgb tex2" [0.8 0.8 0.8] "float uscale" 4 "float vscale" 4
Texture "c3" "float" "checkerboard" "integer dimension" 3 "float tex1" 0.1 "float tex2" 0.9
Material "diffuse" "texture reflectance" "c"
Shape "trianglemesh" "point3 P" [0 0 0 1 0 0 0 1 0] "integer indices" [0 1 2]
)");
  const RGBTextureRef& c = diffuse_reflectance(*s);
  EXPECT_FLOAT_EQ(eval(*s, c, Vec2(0.1f, 0.1f))[0], 0.2f) << "cell (0, 0) is even: tex1";
  EXPECT_FLOAT_EQ(eval(*s, c, Vec2(0.3f, 0.1f))[0], 0.8f) << "cell (1, 0) is odd: tex2";
  EXPECT_FLOAT_EQ(eval(*s, c, Vec2(0.3f, 0.3f))[0], 0.2f);
  double sum = 0.0;
  const int n = 400;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) sum += eval(*s, c, Vec2((i + 0.5f) / n, (j + 0.5f) / n))[0];
  EXPECT_NEAR(sum / (n * n), 0.5, 1e-6);
  // The 3D one, over a 4x4x4 block of cells.
  RGBTextureRef c3{RGB(0.f), int32_t(s->textures.nodes.size() - 1)};
  sum = 0.0;
  const int m = 40;
  for (int i = 0; i < m; ++i)
    for (int j = 0; j < m; ++j)
      for (int k = 0; k < m; ++k)
        sum += eval(*s, c3, Vec2(0.f), Vec3((i + 0.5f) / 10, (j + 0.5f) / 10, (k + 0.5f) / 10))[0];
  EXPECT_NEAR(sum / (m * m * m), 0.5, 1e-6);
}

TEST(Texture, ScaleMixDirectionMixOfConstants) {
  auto s = load_texture_scene(R"(WorldBegin
Texture "a" "spectrum" "constant" "rgb value" [0.2 0.4 0.6]
Texture "half" "float" "constant" "float value" 0.5
Texture "s" "spectrum" "scale" "texture tex" "a" "texture scale" "half"
Texture "m" "spectrum" "mix" "rgb tex1" [1 0 0] "rgb tex2" [0 0 1] "float amount" 0.3
Texture "d" "spectrum" "directionmix" "rgb tex1" [1 0 0] "rgb tex2" [0 0 1] "vector3 dir" [0 0 1]
Material "diffuse" "texture reflectance" "s"
Shape "trianglemesh" "point3 P" [0 0 0 1 0 0 0 1 0] "integer indices" [0 1 2]
Material "diffuse" "texture reflectance" "m"
Shape "trianglemesh" "point3 P" [0 0 0 1 0 0 0 1 0] "integer indices" [0 1 2]
Material "diffuse" "texture reflectance" "d"
Shape "trianglemesh" "point3 P" [0 0 0 1 0 0 0 1 0] "integer indices" [0 1 2]
)");
  RGB sc = eval(*s, s->materials.diffuse[0].reflectance, Vec2(0.5f));
  EXPECT_NEAR(max_component(abs(sc - RGB(0.1f, 0.2f, 0.3f))), 0.f, 1e-6f);
  RGB mx = eval(*s, s->materials.diffuse[1].reflectance, Vec2(0.5f));
  EXPECT_NEAR(max_component(abs(mx - RGB(0.7f, 0.f, 0.3f))), 0.f, 1e-6f);
  const RGBTextureRef& d = s->materials.diffuse[2].reflectance;
  EXPECT_NEAR(max_component(abs(eval(*s, d, Vec2(0.f), Vec3(0.f), Vec3(0, 0, 1)) - RGB(1, 0, 0))), 0.f, 1e-6f) << "|n.dir| = 1: tex1";
  EXPECT_NEAR(max_component(abs(eval(*s, d, Vec2(0.f), Vec3(0.f), Vec3(1, 0, 0)) - RGB(0, 0, 1))), 0.f, 1e-6f) << "|n.dir| = 0: tex2";
  Vec3 n45 = glm::normalize(Vec3(1, 0, 1));
  EXPECT_NEAR(eval(*s, d, Vec2(0.f), Vec3(0.f), n45)[0], std::sqrt(0.5f), 1e-5f);
}

TEST(Texture, BilerpCornersAndCentre) {
  auto s = load_texture_scene(R"(WorldBegin
Texture "b" "float" "bilerp" "float v00" 1 "float v01" 2 "float v10" 3 "float v11" 4
Material "conductor" "texture roughness" "b"
Shape "trianglemesh" "point3 P" [0 0 0 1 0 0 0 1 0] "integer indices" [0 1 2]
)");
  const FloatTextureRef& b = s->materials.conductor[0].roughness.u;
  EXPECT_FLOAT_EQ(eval_float(*s, b, Vec2(0, 0)), 1.f);
  EXPECT_FLOAT_EQ(eval_float(*s, b, Vec2(0, 1)), 2.f);
  EXPECT_FLOAT_EQ(eval_float(*s, b, Vec2(1, 0)), 3.f);
  EXPECT_FLOAT_EQ(eval_float(*s, b, Vec2(1, 1)), 4.f);
  EXPECT_FLOAT_EQ(eval_float(*s, b, Vec2(0.5f, 0.5f)), 2.5f);
}

// A 2x2 image: row 0 (top) red, green; row 1 (bottom) blue, white. pbrt-v4
// puts v = 0 at the bottom of an image.
std::string two_by_two() {
  Image img{2, 2, {1, 0, 0, 0, 1, 0, 0, 0, 1, 1, 1, 1}};
  std::string path = tmp_path("2x2.exr");
  write_image(path, img, {});
  return path;
}

TEST(Texture, ImageOrientationAndWrapModes) {
  std::string file = two_by_two();
  auto s = load_texture_scene(R"(WorldBegin
Texture "rep" "spectrum" "imagemap" "string filter" "point" "string filename" ")" + file + R"("
Texture "clamp" "spectrum" "imagemap" "string filter" "point" "string wrap" "clamp" "string filename" ")" + file + R"("
Texture "black" "spectrum" "imagemap" "string filter" "point" "string wrap" "black" "string filename" ")" + file + R"("
Texture "bil" "spectrum" "imagemap" "string filename" ")" + file + R"("
Material "diffuse" "texture reflectance" "rep"
Shape "trianglemesh" "point3 P" [0 0 0 1 0 0 0 1 0] "integer indices" [0 1 2]
Material "diffuse" "texture reflectance" "clamp"
Shape "trianglemesh" "point3 P" [0 0 0 1 0 0 0 1 0] "integer indices" [0 1 2]
Material "diffuse" "texture reflectance" "black"
Shape "trianglemesh" "point3 P" [0 0 0 1 0 0 0 1 0] "integer indices" [0 1 2]
Material "diffuse" "texture reflectance" "bil"
Shape "trianglemesh" "point3 P" [0 0 0 1 0 0 0 1 0] "integer indices" [0 1 2]
)");
  EXPECT_EQ(s->textures.images.size(), 1u) << "one small file, read once, resident";
  const auto& m = s->materials.diffuse;
  auto at = [&](int i, float u, float v) { return eval(*s, m[size_t(i)].reflectance, Vec2(u, v)); };
  EXPECT_EQ(at(0, 0.25f, 0.25f), RGB(0, 0, 1)) << "bottom left";
  EXPECT_EQ(at(0, 0.75f, 0.25f), RGB(1, 1, 1)) << "bottom right";
  EXPECT_EQ(at(0, 0.25f, 0.75f), RGB(1, 0, 0)) << "top left";
  EXPECT_EQ(at(0, 0.75f, 0.75f), RGB(0, 1, 0)) << "top right";
  EXPECT_EQ(at(0, 1.25f, -0.75f), RGB(0, 0, 1)) << "repeat";
  EXPECT_EQ(at(1, 1.75f, 0.25f), RGB(1, 1, 1)) << "clamp: the right column";
  EXPECT_EQ(at(1, -3.f, 5.f), RGB(1, 0, 0)) << "clamp: the top left corner";
  EXPECT_EQ(at(2, 1.25f, 0.25f), RGB(0, 0, 0)) << "black outside";
  EXPECT_EQ(at(2, 0.25f, 0.25f), RGB(0, 0, 1)) << "black: inside unchanged";
  // Bilinear at the image's centre averages all four texels.
  RGB c = at(3, 0.5f, 0.5f);
  EXPECT_NEAR(max_component(abs(c - RGB(0.5f, 0.5f, 0.5f))), 0.f, 1e-6f);
}

TEST(Texture, EncodingsOfEightBitImages) {
  // Linear 0.2158605 is sRGB 128/255: every texel of the file is byte 128.
  const float linear = 0.2158605f;
  Image img{1, 1, {linear, linear, linear}};
  std::string png = tmp_path("grey.png");
  write_image(png, img, {});
  const float byte = 128.f / 255.f;
  const float srgb = std::pow((byte + 0.055f) / 1.055f, 2.4f);
  struct Case {
    const char* encoding;
    float expected;
  } cases[] = {{"", srgb}, {"\"string encoding\" \"sRGB\"", srgb}, {"\"string encoding\" \"linear\"", byte},
               {"\"string encoding\" \"gamma 2.2\"", std::pow(byte, 2.2f)},
               {"\"bool gamma\" false", byte}, {"\"bool gamma\" true", srgb}};  // pbrt-v3's form
  for (const Case& k : cases) {
    auto s = load_texture_scene(std::string("WorldBegin\nTexture \"t\" \"spectrum\" \"imagemap\" ") + k.encoding +
                  " \"string filename\" \"" + png + "\"\nMaterial \"diffuse\" \"texture reflectance\" \"t\"\n"
                  "Shape \"trianglemesh\" \"point3 P\" [0 0 0 1 0 0 0 1 0] \"integer indices\" [0 1 2]\n");
    // Decoded values are prepared as half floats: 11 significant bits.
    EXPECT_NEAR(eval(*s, diffuse_reflectance(*s), Vec2(0.5f))[0], k.expected, k.expected / 1024.f) << k.encoding;
  }
}

TEST(Texture, NoiseRangeAndMean) {
  EXPECT_EQ(perlin_noise(Vec3(3, -7, 12)), 0.f) << "gradient noise vanishes on the lattice";
  RandomStream s = RandomStream::make(1, 2, 3);
  double sum = 0.0, fsum = 0.0, wsum = 0.0;
  float lo = 1e9f, hi = -1e9f, wlo = 1e9f;
  const int n = 200000;
  for (int i = 0; i < n; ++i) {
    Vec3 p = 100.f * Vec3(s.get1d(), s.get1d(), s.get1d());
    float v = perlin_noise(p);
    sum += v;
    lo = std::min(lo, v);
    hi = std::max(hi, v);
    float f = fbm(p, Vec3(0.f), Vec3(0.f), 0.5f, 8);
    fsum += f;
    EXPECT_LE(std::fabs(f), 2.f * 1.01f);  // at most sum 0.5^i of |noise| <= 1
    float w = turbulence(p, Vec3(0.f), Vec3(0.f), 0.5f, 8);
    wsum += w;
    wlo = std::min(wlo, w);
  }
  EXPECT_NEAR(sum / n, 0.0, 0.01);
  EXPECT_NEAR(fsum / n, 0.0, 0.01);
  EXPECT_GE(lo, -1.01f);
  EXPECT_LE(hi, 1.01f);
  EXPECT_LT(lo, -0.5f) << "noise spans its range";
  EXPECT_GT(hi, 0.5f);
  EXPECT_GT(wlo, 0.f) << "turbulence is positive";
  EXPECT_GT(wsum / n, 0.2);
}

// A conductor whose roughness is a non-constant texture (a mix) with the
// constant's value everywhere renders the very same image.
TEST(Texture, RoughnessTextureEqualsConstant) {
  const std::string scene_head = R"(LookAt 0 2 -3  0 0 0  0 1 0
Camera "perspective" "float fov" 40
Film "rgb" "integer xresolution" 24 "integer yresolution" 24
WorldBegin
LightSource "point" "rgb I" [4 4 4] "point3 from" [1 3 -1]
Texture "r1" "float" "checkerboard" "float tex1" 0.15 "float tex2" 0.15
)";
  const std::string shape = "\nShape \"sphere\" \"float radius\" 1\n";
  auto textured = load_texture_scene(scene_head + R"(Material "conductor" "texture roughness" "r1")" + shape);
  auto constant = load_texture_scene(scene_head + R"(Material "conductor" "float roughness" 0.15)" + shape);
  ASSERT_FALSE(textured->materials.conductor[0].roughness.u.is_constant());
  expect_identical_renders(*textured, *constant, {"path", "bdpt"});
}

// pbrt-v4's (u, v) where a shape has none: a triangle's vertices are (0,0),
// (1,0), (1,1); a bilinear patch runs over [0,1]^2 from p00 to p11.
TEST(Texture, DefaultSurfaceCoordinates) {
  auto s = load_texture_scene(R"(WorldBegin
Shape "trianglemesh" "point3 P" [0 0 0 1 0 0 0 1 0] "integer indices" [0 1 2]
Shape "bilinearmesh" "point3 P" [0 0 0 1 0 0 0 1 0 1 1 0] "integer indices" [0 1 2 3]
)");
  const TriangleMesh& tri = s->shapes.meshes[0];
  EXPECT_EQ(triangle_point(tri, 0, 0.f, 0.f).uv, Vec2(0, 0));
  EXPECT_EQ(triangle_point(tri, 0, 1.f, 0.f).uv, Vec2(1, 0));
  EXPECT_EQ(triangle_point(tri, 0, 0.f, 1.f).uv, Vec2(1, 1));
  const TriangleMesh& patch = s->shapes.meshes[1];
  for (uint32_t t = 0; t < 2; ++t)
    for (Vec2 b : {Vec2(0, 0), Vec2(1, 0), Vec2(0, 1), Vec2(0.3f, 0.3f)}) {
      SurfacePoint sp = triangle_point(patch, t, b.x, b.y);
      EXPECT_NEAR(glm::length(sp.uv - Vec2(sp.p.x, sp.p.y)), 0.f, 1e-6f) << "u, v follow x, y on this patch";
    }
}

// A hit on a triangle or a bilinear patch that lies in a plane z = c is
// exactly on that plane, whatever its barycentrics or (u, v): a 3D
// checkerboard whose boundary is the plane would otherwise flip between
// its two sides from pixel to pixel with the rounding of the barycentrics
// (the quad at z = 0 of tests/conformance/textures.pbrt, 10 units from the
// camera, whose space the hit is reconstructed in). And a triangle's
// vertices and a patch's corners come out exactly.
TEST(Texture, HitsOnAnAxisAlignedTriangleStayOnItsPlane) {
  auto s = load_texture_scene(R"(WorldBegin
Shape "trianglemesh" "point3 P" [-12.5 3.1 -10  7.3 3.1 -10  0.7 9.9 -10] "integer indices" [0 1 2]
Shape "bilinearmesh" "point3 P" [-12.5 3.1 -10  7.3 3.3 -10  0.7 9.9 -10  5.9 11.7 -10] "integer indices" [0 1 2 3]
)");
  const TriangleMesh& tri = s->shapes.meshes[0];
  ASSERT_EQ(s->shapes.patches.size(), 1u) << "(a patch that is not a parallelogram stays a patch)";
  const BilinearPatchSet& patch = s->shapes.patches[0];
  RandomStream rng = RandomStream::make(5, 0, 0);
  for (int i = 0; i < 100000; ++i) {
    // (square roots: numbers of every exponent and full mantissas, as an
    // intersection's quotients are; multiples of 2^-24 round kindly)
    float b1 = std::sqrt(rng.get1d()), b2 = std::sqrt(rng.get1d());
    ASSERT_EQ(bilinear_point(patch, 0, Vec2(b1, b2)).p.z, -10.f) << "u, v " << b1 << ", " << b2;
    if (b1 + b2 > 1.f) b1 = 1.f - b1, b2 = 1.f - b2;
    ASSERT_EQ(triangle_point(tri, 0, b1, b2).p.z, -10.f) << "barycentrics " << b1 << ", " << b2;
  }
  EXPECT_EQ(triangle_point(tri, 0, 0.f, 0.f).p, Vec3(-12.5f, 3.1f, -10.f));
  EXPECT_EQ(triangle_point(tri, 0, 1.f, 0.f).p, Vec3(7.3f, 3.1f, -10.f));
  EXPECT_EQ(triangle_point(tri, 0, 0.f, 1.f).p, Vec3(0.7f, 9.9f, -10.f));
  EXPECT_EQ(bilinear_point(patch, 0, Vec2(1.f, 0.f)).p, Vec3(7.3f, 3.3f, -10.f));
  EXPECT_EQ(bilinear_point(patch, 0, Vec2(1.f, 1.f)).p, Vec3(5.9f, 11.7f, -10.f));
}

void expect_texture_error(const std::string& text, std::initializer_list<const char*> fragments) {
  expect_load_error(text, "t.pbrt", fragments);
}

TEST(Texture, MisuseIsAClearError) {
  const char* tri = "\nShape \"trianglemesh\" \"point3 P\" [0 0 0 1 0 0 0 1 0] \"integer indices\" [0 1 2]\n";
  expect_texture_error(std::string("WorldBegin\nTexture \"f\" \"float\" \"constant\" \"float value\" 1\n"
                           "Material \"diffuse\" \"texture reflectance\" \"f\"") + tri,
               {"t.pbrt:3", "\"f\" is a float texture", "spectrum texture"});
  expect_texture_error(std::string("WorldBegin\nTexture \"c\" \"spectrum\" \"constant\" \"rgb value\" [1 1 1]\n"
                           "Material \"conductor\" \"texture roughness\" \"c\"") + tri,
               {"t.pbrt:3", "spectrum texture", "float texture"});
  expect_texture_error("WorldBegin\nTexture \"i\" \"spectrum\" \"imagemap\" \"string filename\" \"/nonexistent/x.png\"\n",
               {"t.pbrt:2", "x.png", "cannot read image"});
  expect_texture_error("WorldBegin\nTexture \"i\" \"spectrum\" \"checkerboard\" \"integer dimension\" 4\n", {"t.pbrt:2", "dimension"});
  expect_texture_error("WorldBegin\nTexture \"i\" \"spectrum\" \"fbm\"\n", {"t.pbrt:2", "\"fbm\" is not supported"});
  expect_texture_error("WorldBegin\nTexture \"i\" \"spectrum\" \"ptex\" \"string filename\" \"a.ptx\"\n", {"t.pbrt:2", "ptex"});
  expect_texture_error("WorldBegin\nTexture \"i\" \"float\" \"imagemap\" \"string filename\" \"a.png\" \"string wrap\" \"mirror\"\n",
               {"t.pbrt:2", "wrap mode \"mirror\""});
  expect_texture_error("WorldBegin\nTexture \"i\" \"float\" \"imagemap\" \"string filename\" \"a.png\" \"string encoding\" \"gamma x\"\n",
               {"t.pbrt:2", "encoding"});
  expect_texture_error("WorldBegin\nTexture \"i\" \"float\" \"checkerboard\" \"string mapping\" \"cubic\"\n", {"t.pbrt:2", "mapping"});
  // An image with a non-finite texel.
  Image bad{1, 1, {1.f, std::numeric_limits<float>::infinity(), 0.f}};
  std::string path = tmp_path("inf.exr");
  write_image(path, bad, {});
  expect_texture_error("WorldBegin\nTexture \"i\" \"spectrum\" \"imagemap\" \"string filename\" \"" + path + "\"\n",
               {"t.pbrt:2", "non-finite"});
}

}  // namespace
}  // namespace lantern
