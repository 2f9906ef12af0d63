// pbrt-v3 files read as they are: each pbrt-v3 construct renders exactly
// the image of the pbrt-v4 scene pbrt-v4's own upgrade (pbrt --upgrade)
// writes for it, bit for bit; what has no equivalent is a clear error.
#include <gtest/gtest.h>

#include <filesystem>

#include "expect_error.h"
#include "lantern/image.h"
#include "stat_compare.h"

namespace lantern {
namespace {

// A floor and a sphere, lit by a point light unless `lit` is false; `body`
// defines the material "m" (and may add lights), `head` goes before
// WorldBegin.
std::shared_ptr<Scene> scene(const std::string& body, const std::string& head = "", bool lit = true) {
  return load_scene_from_string(head + R"(
LookAt 0 2 -3  0 0.4 0  0 1 0
Camera "perspective" "float fov" [ 40 ]
Film "rgb" "integer xresolution" [ 16 ] "integer yresolution" [ 16 ]
WorldBegin
)" + (lit ? "LightSource \"point\" \"rgb I\" [ 3 3 3 ] \"point3 from\" [ 1 2 -1 ]\n" : "") + body + R"(
NamedMaterial "m"
Shape "sphere" "float radius" [ 0.5 ]
Shape "trianglemesh" "point3 P" [ -3 -0.5 -3  3 -0.5 -3  3 -0.5 3  -3 -0.5 3 ] "integer indices" [ 0 1 2 0 2 3 ]
  "point2 uv" [ 0 0 1 0 1 1 0 1 ]
)",
                                "v3.pbrt");
}

struct Pair {
  const char* what;
  const char* v3;
  const char* v4;
};

TEST(PbrtV3, ConstructsRenderAsTheirUpgrades) {
  const Pair pairs[] = {
      {"uber", R"(MakeNamedMaterial "m" "string type" "uber" "color Kd" [ 0.6 0.3 0.2 ] "color Ks" [ 0.2 0.2 0.2 ]
          "float roughness" [ 0.05 ] "float index" [ 1.4 ])",
       R"(MakeNamedMaterial "m" "string type" "coateddiffuse" "rgb reflectance" [ 0.6 0.3 0.2 ]
          "float roughness" [ 0.05 ] "float eta" [ 1.4 ])"},
      {"uber without Ks", R"(MakeNamedMaterial "m" "string type" "uber" "color Kd" [ 0.6 0.3 0.2 ] "color Ks" [ 0 0 0 ])",
       R"(MakeNamedMaterial "m" "string type" "diffuse" "rgb reflectance" [ 0.6 0.3 0.2 ])"},
      {"substrate", R"(MakeNamedMaterial "m" "string type" "substrate" "color Kd" [ 0.2 0.5 0.3 ] "color Ks" [ 1 1 1 ]
          "float uroughness" [ 0.1 ] "float vroughness" [ 0.2 ])",
       R"(MakeNamedMaterial "m" "string type" "coateddiffuse" "rgb reflectance" [ 0.2 0.5 0.3 ]
          "float uroughness" [ 0.1 ] "float vroughness" [ 0.2 ])"},
      {"translucent", R"(MakeNamedMaterial "m" "string type" "translucent" "color Kd" [ 0.5 0.4 0.3 ])",
       R"(MakeNamedMaterial "m" "string type" "diffusetransmission" "rgb transmittance" [ 0.5 0.4 0.3 ])"},
      {"mix", R"(MakeNamedMaterial "a" "string type" "matte" "color Kd" [ 0.7 0.1 0.1 ]
          MakeNamedMaterial "b" "string type" "metal"
          MakeNamedMaterial "m" "string type" "mix" "string namedmaterial1" "a" "string namedmaterial2" "b"
          "color amount" [ 0.3 0.3 0.3 ])",
       R"(MakeNamedMaterial "a" "string type" "diffuse" "rgb reflectance" [ 0.7 0.1 0.1 ]
          MakeNamedMaterial "b" "string type" "metal"
          MakeNamedMaterial "m" "string type" "mix" "string materials" [ "b" "a" ] "float amount" [ 0.3 ])"},
      {"bumpmap and a scale texture", R"(Texture "c" "float" "checkerboard" "float uscale" [ 8 ] "float vscale" [ 8 ]
          Texture "s" "float" "scale" "texture tex1" "c" "float tex2" [ 0.02 ]
          Texture "k" "color" "scale" "color tex1" [ 0.5 0.5 0.5 ] "color tex2" [ 0.9 0.5 0.2 ]
          MakeNamedMaterial "m" "string type" "matte" "texture Kd" "k" "texture bumpmap" "s")",
       R"(Texture "c" "float" "checkerboard" "float uscale" [ 8 ] "float vscale" [ 8 ]
          Texture "s" "float" "scale" "texture tex" "c" "float scale" [ 0.02 ]
          Texture "k" "spectrum" "scale" "rgb tex" [ 0.9 0.5 0.2 ] "float scale" [ 0.5 ]
          MakeNamedMaterial "m" "string type" "diffuse" "texture reflectance" "k" "texture displacement" "s")"},
      {"plastic without Ks", R"(MakeNamedMaterial "m" "string type" "plastic" "color Kd" [ 0.6 0.3 0.2 ] "color Ks" [ 0 0 0 ]
          "float roughness" [ 0.2 ])",
       R"(MakeNamedMaterial "m" "string type" "diffuse" "rgb reflectance" [ 0.6 0.3 0.2 ])"},
      {"disney is a diffuse of its colour", R"(MakeNamedMaterial "m" "string type" "disney" "color color" [ 0.3 0.6 0.2 ]
          "float metallic" [ 0.5 ] "float roughness" [ 0.2 ])",
       R"(MakeNamedMaterial "m" "string type" "diffuse" "rgb reflectance" [ 0.3 0.6 0.2 ])"},
      {"an unknown material is matte", R"(MakeNamedMaterial "m" "string type" "BUSH1" "color Kd" [ 0.2 0.5 0.1 ])",
       R"(MakeNamedMaterial "m" "string type" "diffuse" "rgb reflectance" [ 0.2 0.5 0.1 ])"},
      {"area light with a blackbody temperature and scale",
       R"(AttributeBegin AreaLightSource "area" "blackbody L" [ 4000 2 ] Translate 0 1.2 0 Shape "sphere" "float radius" [ 0.2 ]
          AttributeEnd MakeNamedMaterial "m" "string type" "matte")",
       R"(AttributeBegin AreaLightSource "diffuse" "blackbody L" [ 4000 ] "float scale" [ 2 ] Translate 0 1.2 0
          Shape "sphere" "float radius" [ 0.2 ] AttributeEnd MakeNamedMaterial "m" "string type" "diffuse")"},
      {"colour light scale", R"(LightSource "spot" "color I" [ 2 2 2 ] "color scale" [ 1 0.5 0.25 ] "point3 from" [ 0 3 0 ]
          "point3 to" [ 0 0 0 ] MakeNamedMaterial "m" "string type" "matte")",
       R"(LightSource "spot" "rgb I" [ 2 1 0.5 ] "point3 from" [ 0 3 0 ] "point3 to" [ 0 0 0 ]
          MakeNamedMaterial "m" "string type" "diffuse")"},
  };
  for (const Pair& p : pairs) {
    SCOPED_TRACE(p.what);
    expect_identical_renders(*scene(p.v3), *scene(p.v4), {"path", "bdpt"});
  }
  // pbrt-v3's sampler names and its "point"-typed mesh positions and
  // "float"-typed uvs.
  expect_identical_renders(*scene("MakeNamedMaterial \"m\" \"string type\" \"matte\"", "Sampler \"lowdiscrepancy\"\n"),
                           *scene("MakeNamedMaterial \"m\" \"string type\" \"diffuse\"", "Sampler \"paddedsobol\"\n"),
                           {"path"});
  expect_identical_renders(
      *scene(R"(MakeNamedMaterial "m" "string type" "matte"
          Shape "trianglemesh" "point P" [ -1 0 1  1 0 1  0 1 1 ] "integer indices" [ 0 1 2 ] "float uv" [ 0 0 1 0 0 1 ])"),
      *scene(R"(MakeNamedMaterial "m" "string type" "diffuse"
          Shape "trianglemesh" "point3 P" [ -1 0 1  1 0 1  0 1 1 ] "integer indices" [ 0 1 2 ] "point2 uv" [ 0 0 1 0 0 1 ])"),
      {"path"});
}

// pbrt-v3's environment light takes "L" and "filename" together: L scales
// the map (pbrt-v4 refuses the pair).
TEST(PbrtV3, EnvironmentMapScaledByL) {
  auto dir = std::filesystem::temp_directory_path() / "lantern-v3-test";
  std::filesystem::create_directories(dir);
  std::vector<float> rgb;
  for (int i = 0; i < 16 * 8; ++i) rgb.insert(rgb.end(), {0.2f + 0.01f * float(i % 16), 0.3f, 0.4f});
  write_image((dir / "sky.exr").string(), Image{16, 8, rgb}, {});
  const std::string mat = "MakeNamedMaterial \"m\" \"string type\" \"matte\"\n";
  const std::string sky = "LightSource \"infinite\" \"string filename\" \"" + (dir / "sky.exr").string() + "\" ";
  auto v3 = scene(mat + sky + "\"color L\" [ 0.5 1 2 ]", "", false);
  auto v4 = scene(mat + sky, "", false);
  RenderOptions o;
  o.spp = 8;
  Image a = render(*v3, o).image, b = render(*v4, o).image;
  double ra = 0, rb = 0, ba = 0, bb = 0;
  for (size_t i = 0; i < a.rgb.size(); i += 3) ra += a.rgb[i], rb += b.rgb[i], ba += a.rgb[i + 2], bb += b.rgb[i + 2];
  EXPECT_NEAR(ra / rb, 0.5, 1e-4);
  EXPECT_NEAR(ba / bb, 2.0, 1e-4);
}

// pbrt-v3's imagemap flags: "bool gamma" for the encoding, "bool
// trilinear" for the filter.
TEST(PbrtV3, ImagemapFlags) {
  auto dir = std::filesystem::temp_directory_path() / "lantern-v3-test";
  std::filesystem::create_directories(dir);
  std::vector<float> rgb;
  for (int i = 0; i < 64 * 64; ++i) rgb.insert(rgb.end(), {float(i % 7) / 7.f, float(i % 5) / 5.f, 0.5f});
  const std::string file = (dir / "tex.exr").string();
  write_image(file, Image{64, 64, rgb}, {});
  auto with = [&](const std::string& flags) {
    return scene("Texture \"t\" \"color\" \"imagemap\" \"string filename\" \"" + file + "\" " + flags +
                 "\nMakeNamedMaterial \"m\" \"string type\" \"matte\" \"texture Kd\" \"t\"");
  };
  expect_identical_renders(*with("\"bool gamma\" true \"bool trilinear\" true"),
                           *with("\"string encoding\" \"sRGB\" \"string filter\" \"trilinear\""), {"path"});
  expect_identical_renders(*with("\"bool gamma\" false \"bool trilinear\" false"),
                           *with("\"string encoding\" \"linear\" \"string filter\" \"bilinear\""), {"path"});
}

// pbrt-v3 renders a material type it does not know as matte and says so.
TEST(PbrtV3, UnknownMaterialWarnsWithItsLine) {
  std::vector<std::string> warnings;
  LoadOptions o;
  o.warn = [&](const std::string& w) { warnings.push_back(w); };
  auto s = load_scene_from_string("WorldBegin\nMaterial \"BUSH1\" \"color Kd\" [0.2 0.5 0.1]\nShape \"sphere\"\n",
                                  "bush.pbrt", o);
  ASSERT_EQ(s->materials.diffuse.size(), 1u);
  EXPECT_EQ(s->materials.diffuse[0].reflectance.value, RGB(0.2f, 0.5f, 0.1f));
  ASSERT_FALSE(warnings.empty());
  EXPECT_NE(warnings[0].find("bush.pbrt:2"), std::string::npos) << warnings[0];
  EXPECT_NE(warnings[0].find("\"BUSH1\" is unknown"), std::string::npos) << warnings[0];
}

// pbrt-v3's film scale and sample clamp, filter widths and gaussian falloff,
// and environment camera, as pbrt-v4's upgrade writes them: Film "scale" s
// is "iso" 100 s, "maxsampleluminance" is "maxcomponentvalue", "xwidth" and
// "ywidth" are the radii, "alpha" a is "sigma" 1 / sqrt(2 a), and
// "environment" is the spherical camera's equirectangular mapping.
TEST(PbrtV3, FilmFilterAndCameraRenderAsTheirUpgrades) {
  const std::string world = R"(
WorldBegin
LightSource "infinite" "rgb L" [ 0.4 0.5 0.6 ]
LightSource "point" "rgb I" [ 30 30 30 ] "point3 from" [ 1 2 -1 ]
Material "diffuse" "rgb reflectance" [ 0.7 0.3 0.2 ]
Shape "sphere" "float radius" [ 0.5 ]
Shape "trianglemesh" "point3 P" [ -3 -0.5 -3  3 -0.5 -3  3 -0.5 3  -3 -0.5 3 ] "integer indices" [ 0 1 2 0 2 3 ]
)";
  auto v3 = load_scene_from_string(R"(LookAt 0 0.5 -2  0 0 0  0 1 0
Camera "environment"
Film "image" "integer xresolution" [ 32 ] "integer yresolution" [ 16 ] "float scale" [ 2 ] "float maxsampleluminance" [ 3 ]
PixelFilter "gaussian" "float xwidth" [ 1 ] "float ywidth" [ 1.25 ] "float alpha" [ 0.5 ]
)" + world, "v3.pbrt");
  auto v4 = load_scene_from_string(R"(LookAt 0 0.5 -2  0 0 0  0 1 0
Camera "spherical" "string mapping" "equirectangular"
Film "rgb" "integer xresolution" [ 32 ] "integer yresolution" [ 16 ] "float iso" [ 200 ] "float maxcomponentvalue" [ 3 ]
PixelFilter "gaussian" "float xradius" [ 1 ] "float yradius" [ 1.25 ] "float sigma" [ 1 ]
)" + world, "v4.pbrt");
  EXPECT_EQ(v3->settings.iso, 200.f);
  EXPECT_EQ(v3->settings.max_component_value, 3.f);
  EXPECT_EQ(v3->filter.radius, Vec2(1.f, 1.25f));  // (pbrt-v4's defaults: 1.5, sigma 0.5)
  EXPECT_EQ(v3->filter.sigma, 1.f);
  expect_identical_renders(*v3, *v4, {"path", "bdpt"});
}

// pbrt-v3's "heterogeneous" medium is pbrt-v4's "uniformgrid".
TEST(PbrtV3, HeterogeneousMediumIsAUniformGrid) {
  auto with = [](const char* type) {
    return load_scene_from_string(std::string(R"(LookAt 0 0.5 -3  0 0 0  0 1 0
Camera "perspective" "float fov" [ 40 ]
Film "rgb" "integer xresolution" [ 16 ] "integer yresolution" [ 16 ]
WorldBegin
LightSource "point" "rgb I" [ 8 8 8 ] "point3 from" [ 1 2 -1 ]
MakeNamedMedium "fog" "string type" ")") + type + R"(" "integer nx" [ 2 ] "integer ny" [ 1 ] "integer nz" [ 2 ]
  "float density" [ 0.2 1.5 0.7 3 ] "point3 p0" [ -1 -1 -1 ] "point3 p1" [ 1 1 1 ]
  "rgb sigma_a" [ 0.2 0.3 0.4 ] "rgb sigma_s" [ 1 0.8 0.6 ]
AttributeBegin
  MediumInterface "fog" ""
  Material "interface"
  Shape "sphere" "float radius" [ 0.9 ]
AttributeEnd
Material "diffuse"
Shape "trianglemesh" "point3 P" [ -3 -1 -3  3 -1 -3  3 -1 3  -3 -1 3 ] "integer indices" [ 0 1 2 0 2 3 ]
)",
                                  "fog.pbrt");
  };
  expect_identical_renders(*with("heterogeneous"), *with("uniformgrid"), {"path", "bdpt"});
}

TEST(PbrtV3, UnsupportedMaterialsAreClearErrors) {
  expect_load_error("WorldBegin\nMaterial \"fourier\" \"string bsdffile\" \"x.bsdf\"\n", "f.pbrt", {"f.pbrt:2", "fourier"});
  expect_load_error("WorldBegin\nMaterial \"uber\" \"color opacity\" [ 0.5 0.5 0.5 ]\n", "u.pbrt",
                    {"u.pbrt:2", "opacity", "alpha"});
}

}  // namespace
}  // namespace lantern
