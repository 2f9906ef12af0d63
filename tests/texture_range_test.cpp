// Bounds on float textures (TexturePools::range) against the values the
// textures take at random points, directions and footprints, and against
// closed forms; and which materials may be specular
// (material/may_be_specular.h), the question the bounds answer.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <string>
#include <unistd.h>
#include <vector>

#include "lantern/image.h"
#include "lantern/render.h"
#include "material/may_be_specular.h"
#include "math/rng.h"
#include "scene/scene.h"

namespace lantern {
namespace {

// A scene whose conductors take, in order, each given float texture (or
// value) as their roughness: "texture roughness" "name" or "float roughness" [v].
std::shared_ptr<Scene> roughness_scene(const std::string& textures, const std::vector<std::string>& roughness,
                                       const LoadOptions& options = {}) {
  std::string text = "WorldBegin\n" + textures + "\n";
  for (const std::string& r : roughness)
    text += "Material \"conductor\" " + r + "\nShape \"sphere\" \"float radius\" [ 0.1 ]\n";
  return load_scene_from_string(text, "range.pbrt", options);
}

const FloatTextureRef& roughness_of(const Scene& s, size_t i) { return s.materials.conductor.at(i).roughness.u; }

const char* const kTextures = R"(
Texture "checks" "float" "checkerboard" "float uscale" [ 7 ] "float vscale" [ 3 ] "float tex1" [ 0.02 ] "float tex2" [ 0.25 ]
Texture "checks3d" "float" "checkerboard" "integer dimension" [ 3 ] "float tex1" [ -1 ] "float tex2" [ 2 ]
Texture "dots" "float" "dots" "float uscale" [ 5 ] "float vscale" [ 5 ] "float inside" [ 0.7 ] "float outside" [ 0.1 ]
Texture "wear" "float" "wrinkled" "integer octaves" [ 4 ]
Texture "worn" "float" "mix" "float tex1" [ 0.03 ] "float tex2" [ 0.2 ] "texture amount" "wear"
Texture "signed" "float" "scale" "texture tex" "checks3d" "float scale" [ -0.5 ]
Texture "scaledwear" "float" "scale" "texture tex" "wear" "texture scale" "dots"
Texture "facing" "float" "directionmix" "float tex1" [ 0.4 ] "float tex2" [ 0.9 ] "vector3 dir" [ 0 0 1 ]
Texture "blend" "float" "mix" "texture tex1" "checks" "texture tex2" "dots" "texture amount" "checks"
Texture "noise" "float" "fbm"
Texture "gust" "float" "windy"
Texture "negwear" "float" "wrinkled" "float roughness" [ -0.5 ]
Texture "noisemix" "float" "mix" "texture tex1" "noise" "float tex2" [ 0.5 ] "float amount" [ 0.3 ]
)";
const char* const kNames[] = {"checks", "checks3d", "dots",  "wear", "worn",    "signed",  "scaledwear",
                              "facing", "blend",    "noise", "gust", "negwear", "noisemix"};

std::shared_ptr<Scene> named_textures() {
  std::vector<std::string> r;
  for (const char* n : kNames) r.push_back(std::string("\"texture roughness\" \"") + n + "\"");
  return roughness_scene(kTextures, r);
}

// Evaluates each texture (the scene's conductors' roughness, in order) at
// 40,000 random points, normals, (u, v) and footprints: every value stays
// within its bounds (up to the blend's rounding), and finite bounds are
// reached to within a tenth of their width, so they are the closed forms,
// not merely bounds.
void expect_values_within_bounds(const Scene& s, const std::vector<std::string>& names) {
  RandomStream rng = RandomStream::make(11, 12, 13);
  for (size_t t = 0; t < names.size(); ++t) {
    const FloatTextureRef& ref = roughness_of(s, t);
    const ValueRange r = s.textures.range(ref);
    float lo = kInfinity, hi = -kInfinity;
    for (int i = 0; i < 40000; ++i) {
      Footprint fp;
      const float f = i % 2 ? 0.f : 0.05f * rng.get1d();  // (filtered and point lookups)
      fp.duvdx = Vec2(f, 0.f);
      fp.duvdy = Vec2(0.f, f);
      fp.dpdx = Vec3(f, 0.f, 0.f);
      fp.dpdy = Vec3(0.f, f, 0.f);
      const Vec3 n = glm::normalize(Vec3(rng.get1d() - 0.5f, rng.get1d() - 0.5f, rng.get1d() - 0.5f));
      const Vec3 p = 10.f * Vec3(rng.get1d(), rng.get1d(), rng.get1d());
      const TextureContext c{p, n, 4.f * Vec2(rng.get1d(), rng.get1d()) - Vec2(1.f), &fp};
      const float v = s.textures.evaluate_float(ref, c);
      lo = std::min(lo, v);
      hi = std::max(hi, v);
      ASSERT_TRUE(v >= r.lo - 1e-6f && v <= r.hi + 1e-6f)
          << names[t] << ": " << v << " outside [" << r.lo << ", " << r.hi << "]";
    }
    if (std::isfinite(r.lo) && std::isfinite(r.hi)) {
      EXPECT_LE(lo, r.lo + 0.1f * (r.hi - r.lo)) << names[t];
      EXPECT_GE(hi, r.hi - 0.1f * (r.hi - r.lo)) << names[t];
    }
  }
}

TEST(TextureRange, ValuesStayWithinTheBoundsAndReachThem) {
  expect_values_within_bounds(*named_textures(), std::vector<std::string>(std::begin(kNames), std::end(kNames)));
}

// An image held in memory spans its texels' channels (a float lookup reads
// the mean of RGB, or the first channel with the point filter), with 0
// where the black wrap reads outside it, scaled and inverted.
TEST(TextureRange, ResidentImagesSpanTheirTexels) {
  const std::string file = (std::filesystem::temp_directory_path() /
                            ("lantern-range-" + std::to_string(::getpid()) + ".exr")).string();
  write_image(file, Image{2, 2, {0.2f, 0.3f, 0.4f, 0.9f, 0.8f, 0.7f, 0.5f, 0.5f, 0.5f, 0.25f, 0.6f, 0.35f}}, {});
  const std::string image = "\"float\" \"imagemap\" \"string filename\" \"" + file + "\"";
  const std::vector<std::string> names = {"point", "black", "plain", "scaled", "inverted"};
  const std::string point = " \"string filter\" \"point\"";
  std::string textures;
  const std::string params[] = {point, point + " \"string wrap\" \"black\"", "", " \"float scale\" [ -2 ]",
                                " \"bool invert\" true"};
  std::vector<std::string> materials;
  for (size_t t = 0; t < names.size(); ++t) {
    textures += "Texture \"" + names[t] + "\" " + image + params[t] + "\n";
    materials.push_back("\"texture roughness\" \"" + names[t] + "\"");
  }
  const auto s = roughness_scene(textures, materials);
  std::filesystem::remove(file);
  ASSERT_EQ(s->textures.images.size(), 1u) << "resident";
  const ValueRange expected[] = {{0.2f, 0.9f}, {0.f, 0.9f}, {0.2f, 0.9f}, {-1.8f, -0.4f}, {0.1f, 0.8f}};
  for (size_t t = 0; t < names.size(); ++t) {
    const ValueRange r = s->textures.range(roughness_of(*s, t));
    EXPECT_NEAR(r.lo, expected[t].lo, 2e-3f) << names[t];  // (the file's half floats)
    EXPECT_NEAR(r.hi, expected[t].hi, 2e-3f) << names[t];
  }
  // (bilinear lookups of the mean of RGB, from 0.3 to 0.8, reach neither
  // bound; point lookups read the first channel, from 0.2 to 0.9)
  expect_values_within_bounds(*s, {"point", "black"});
}

// An image read through the texture cache (a trilinear filter) spans the
// texels its prepared file holds, as recorded when the file was made and
// read back when a later load finds the file made: an 8-bit PNG of greys
// from 0.1 to 0.9 (sRGB-encoded, decoded at preparation), with 0 where the
// black wrap reads outside it.
TEST(TextureRange, CachedImagesSpanTheirPreparedTexels) {
  const auto dir = std::filesystem::temp_directory_path() / ("lantern-range-cache-" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  const std::string file = (dir / "greys.png").string();
  write_image(file, Image{2, 2, {0.1f, 0.1f, 0.1f, 0.3f, 0.3f, 0.3f, 0.6f, 0.6f, 0.6f, 0.9f, 0.9f, 0.9f}}, {});
  const std::string image =
      "\"float\" \"imagemap\" \"string filename\" \"" + file + "\" \"string filter\" \"trilinear\"";
  const std::string textures =
      "Texture \"plain\" " + image + "\nTexture \"black\" " + image + " \"string wrap\" \"black\"\n";
  LoadOptions options;
  options.texture_directory = (dir / "prepared").string();
  for (const char* load : {"preparing the file", "finding it prepared"}) {
    const auto s =
        roughness_scene(textures, {"\"texture roughness\" \"plain\"", "\"texture roughness\" \"black\""}, options);
    ASSERT_TRUE(s->textures.images.empty()) << "read through the cache";
    const ValueRange plain = s->textures.range(roughness_of(*s, 0)), black = s->textures.range(roughness_of(*s, 1));
    EXPECT_NEAR(plain.lo, 0.1f, 5e-3f) << load;  // (8-bit sRGB steps: 0.008 of linear at 0.9)
    EXPECT_NEAR(plain.hi, 0.9f, 5e-3f) << load;
    EXPECT_EQ(black.lo, 0.f) << load;
    EXPECT_EQ(black.hi, plain.hi) << load;
    expect_values_within_bounds(*s, {"plain", "black"});
  }
  std::filesystem::remove_all(dir);
}

// The bounds by kind: patterns hull their two values, scale multiplies
// bounds, mix blends them (by an amount bounded on one side only, for a
// wrinkled one), the signed noises and a wrinkled texture of negative
// roughness are unbounded.
TEST(TextureRange, BoundsByKind) {
  const auto s = named_textures();
  const auto range = [&](const char* name) {
    for (size_t t = 0; t < std::size(kNames); ++t)
      if (std::string(kNames[t]) == name) return s->textures.range(roughness_of(*s, t));
    ADD_FAILURE() << name;
    return ValueRange{};
  };
  const auto expect = [&](const char* name, float lo, float hi) {
    const ValueRange r = range(name);
    EXPECT_FLOAT_EQ(r.lo, lo) << name;
    EXPECT_FLOAT_EQ(r.hi, hi) << name;
  };
  expect("checks", 0.02f, 0.25f);
  expect("checks3d", -1.f, 2.f);
  expect("dots", 0.1f, 0.7f);
  expect("wear", 0.f, kInfinity);
  expect("worn", 0.03f, kInfinity);
  expect("signed", -1.f, 0.5f);
  expect("scaledwear", 0.f, kInfinity);
  expect("facing", 0.4f, 0.9f);
  expect("blend", 0.02f + 0.02f * 0.08f, 0.25f + 0.25f * 0.45f);  // (tex1 + amount (tex2 - tex1))
  for (const char* wide : {"noise", "gust", "negwear", "noisemix"}) expect(wide, -kInfinity, kInfinity);
}

struct SpecularCase {
  const char* material;
  bool specular;
};

// Which materials may scatter through a delta lobe: pbrt-v4's
// effectively smooth distributions (alpha below 1e-3, after the square
// root that remaproughness takes), an index of 1, a thin dielectric, a
// mirror, a smooth coat or a smooth conductor under one, either side of a
// mix; a textured roughness by its bounds.
TEST(MayBeSpecular, FollowsTheRoughnessBounds) {
  const SpecularCase cases[] = {
      {R"("diffuse")", false},
      {R"("conductor" "float roughness" [ 0 ])", true},
      {R"("conductor" "float roughness" [ 0.01 ])", false},
      {R"("conductor" "float roughness" [ 0.0000009 ])", true},
      {R"("conductor" "float roughness" [ 0.0005 ] "bool remaproughness" false)", true},
      {R"("conductor" "float roughness" [ 0.002 ] "bool remaproughness" false)", false},
      {R"("conductor" "float uroughness" [ 0.2 ] "float vroughness" [ 0 ])", false},
      {R"("conductor" "texture roughness" "checks")", false},
      {R"("conductor" "texture roughness" "checks0")", true},
      {R"("conductor" "texture roughness" "worn")", false},
      {R"("conductor" "texture roughness" "noise")", true},
      {R"("mirror")", true},
      {R"("dielectric" "float roughness" [ 0.1 ])", false},
      {R"("dielectric" "float roughness" [ 0.1 ] "float eta" [ 1 ])", true},
      {R"("dielectric")", true},
      {R"("thindielectric")", true},
      {R"("coateddiffuse")", true},
      {R"("coateddiffuse" "float roughness" [ 0.1 ])", false},
      {R"("coatedconductor" "float interface.roughness" [ 0.1 ])", true},
      {R"("coatedconductor" "float interface.roughness" [ 0.1 ] "float conductor.roughness" [ 0.1 ])", false},
      {R"("diffusetransmission")", false},
      {R"("hair")", false},
  };
  const std::string textures = R"(
Texture "checks" "float" "checkerboard" "float tex1" [ 0.02 ] "float tex2" [ 0.25 ]
Texture "checks0" "float" "checkerboard" "float tex1" [ 0 ] "float tex2" [ 0.25 ]
Texture "wear" "float" "wrinkled"
Texture "worn" "float" "mix" "float tex1" [ 0.03 ] "float tex2" [ 0.2 ] "texture amount" "wear"
Texture "noise" "float" "fbm"
)";
  for (const SpecularCase& c : cases) {
    const auto s = load_scene_from_string("WorldBegin\n" + textures + "MakeNamedMaterial \"m\" \"string type\" " +
                                              c.material + "\nNamedMaterial \"m\"\nShape \"sphere\"\n",
                                          "specular.pbrt", {});
    EXPECT_EQ(!kind_that_may_be_specular(s->materials, s->textures).empty(), c.specular) << c.material;
  }
  // A mix is specular where either of its materials may be.
  const auto mix = load_scene_from_string(R"(WorldBegin
MakeNamedMaterial "rough" "string type" "conductor" "float roughness" [ 0.1 ]
MakeNamedMaterial "smooth" "string type" "dielectric"
MakeNamedMaterial "both" "string type" "mix" "string materials" [ "rough" "smooth" ] "float amount" [ 0.1 ]
MakeNamedMaterial "rough2" "string type" "conductor" "float roughness" [ 0.2 ]
MakeNamedMaterial "neither" "string type" "mix" "string materials" [ "rough" "rough2" ]
)",
                                          "mix.pbrt", {});
  ASSERT_EQ(mix->materials.mix.size(), 2u);
  EXPECT_TRUE(may_be_specular(mix->materials, mix->textures, MaterialHandle::make(MaterialKind::Mix, 0)));
  EXPECT_FALSE(may_be_specular(mix->materials, mix->textures, MaterialHandle::make(MaterialKind::Mix, 1)));
}

}  // namespace
}  // namespace lantern
