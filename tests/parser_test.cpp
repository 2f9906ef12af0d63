// The pbrt importer: every supported directive lands in the right component
// pool, and every kind of malformed input gets a clear error with its place.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "expect_error.h"
#include "scene/scene.h"

namespace lantern {
namespace {

std::shared_ptr<Scene> load(const std::string& text, std::vector<std::string>* warnings = nullptr, bool lenient = false) {
  LoadOptions o;
  o.lenient = lenient;
  o.warn = [warnings](const std::string& w) {
    if (warnings) warnings->push_back(w);
  };
  return load_scene_from_string(text, "t.pbrt", o);
}

// Loads and expects an InputError whose message contains every fragment.
void expect_error(const std::string& text, std::initializer_list<const char*> fragments) {
  expect_load_error(text, "t.pbrt", fragments);
}

const char* kEverything = R"(
# comment
Film "rgb" "integer xresolution" [ 64 ] "integer yresolution" 32 "string filename" "x.exr"
Sampler "sobol" "integer pixelsamples" 8
Integrator "path" "integer maxdepth" [ 7 ]
PixelFilter "triangle" "float xradius" 1 "float yradius" 1
Scale -1 1 1
LookAt 0 0 -5  0 0 0  0 1 0
Camera "perspective" "float fov" 45 "float lensradius" 0.1 "float focaldistance" 5
WorldBegin
Texture "checks" "spectrum" "constant" "rgb value" [0.2 0.3 0.4]
Texture "rough" "float" "constant" "float value" 0.2
MakeNamedMaterial "red" "string type" "diffuse" "rgb reflectance" [0.8 0.1 0.1]
MakeNamedMaterial "gold" "string type" "conductor" "spectrum eta" "metal-Au-eta" "spectrum k" "metal-Au-k" "texture roughness" "rough"
MakeNamedMaterial "glass" "string type" "dielectric" "float eta" 1.33
MakeNamedMaterial "plastic" "string type" "coateddiffuse" "texture reflectance" "checks" "float roughness" 0.1
Material "matte" "rgb Kd" [0.5 0.5 0.5]
Material "plastic" "rgb Kd" [0.5 0.5 0.5] "float roughness" 0.05
Material "mirror"
Material "metal"
Material "glass"
AttributeBegin
  Translate 1 2 3
  Rotate 90 0 1 0
  ConcatTransform [1 0 0 0 0 1 0 0 0 0 1 0 0 0 0 1]
  CoordinateSystem "mine"
  NamedMaterial "red"
  Shape "trianglemesh" "point3 P" [0 0 0 1 0 0 0 1 0] "integer indices" [0 1 2] "normal N" [0 0 1 0 0 1 0 0 1] "point2 uv" [0 0 1 0 0 1]
AttributeEnd
AttributeBegin
  Identity
  CoordSysTransform "mine"
  Transform [1 0 0 0 0 1 0 0 0 0 1 0 0 0 4 1]
  NamedMaterial "gold"
  ReverseOrientation
  AreaLightSource "diffuse" "rgb L" [4 4 4] "bool twosided" true
  Shape "sphere" "float radius" 0.5
AttributeEnd
NamedMaterial "glass"
Shape "bilinearmesh" "point3 P" [0 0 0 1 0 0 0 1 0 1 1 0] "integer indices" [0 1 2 3]
NamedMaterial "plastic"
Shape "trianglemesh" "point3 P" [0 0 0 1 0 0 0 1 0]
LightSource "point" "rgb I" [1 1 1] "point3 from" [0 5 0]
LightSource "spot" "blackbody I" 3000 "point3 from" [0 5 0] "point3 to" [0 0 0] "float coneangle" 20
LightSource "distant" "rgb L" [1 1 1] "point3 from" [0 1 0] "point3 to" [0 0 0]
LightSource "infinite" "rgb L" [0.1 0.1 0.1]
WorldEnd
)";

TEST(Parser, EveryDirectiveLandsInItsPool) {
  std::vector<std::string> warnings;
  // In world space, so that positions read back as written.
  auto s = load("Option \"string renderingcoordinatesystem\" \"world\"\n" + std::string(kEverything), &warnings);
  EXPECT_EQ(s->settings.width, 64);
  EXPECT_EQ(s->settings.height, 32);
  EXPECT_EQ(s->settings.spp, 8);
  EXPECT_EQ(s->settings.maxdepth, 7);
  EXPECT_EQ(s->settings.output, "x.exr");
  EXPECT_EQ(s->filter.type, PixelFilter::Type::Triangle);
  EXPECT_FLOAT_EQ(s->camera.fov_degrees, 45.f);
  EXPECT_FLOAT_EQ(s->camera.lens_radius, 0.1f);
  EXPECT_EQ(s->shapes.meshes.size(), 3u);
  EXPECT_EQ(s->shapes.spheres.size(), 1u);
  EXPECT_EQ(s->shapes.meshes[1].triangles.size(), 2u) << "a bilinear patch is two triangles";
  EXPECT_EQ(s->materials.diffuse.size(), 2u);
  EXPECT_EQ(s->materials.conductor.size(), 3u);
  EXPECT_EQ(s->materials.dielectric.size(), 2u);
  EXPECT_EQ(s->materials.coated_diffuse.size(), 2u);
  {
    TrowbridgeReitz d = s->materials.conductor[0].roughness.distribution(s->textures, TextureContext{});
    EXPECT_NEAR(d.alpha_x, std::sqrt(0.2f), 1e-6f) << "roughness from a float texture, remapped";
  }
  EXPECT_EQ(s->lights.area.size(), 1u);
  EXPECT_TRUE(s->lights.area[0].two_sided);
  EXPECT_EQ(s->lights.point.size(), 1u);
  EXPECT_EQ(s->lights.spot.size(), 1u);
  EXPECT_EQ(s->lights.distant.size(), 1u);
  EXPECT_EQ(s->lights.infinite.size(), 1u);
  // The sphere went through CoordSysTransform then Transform: centre (0,0,4).
  EXPECT_NEAR(s->shapes.spheres[0].center.z, 4.f, 1e-5f);
  EXPECT_TRUE(s->shapes.spheres[0].flip_normal);
  // The first mesh: Translate(1,2,3) then Rotate: vertex 0 lands at (1,2,3).
  EXPECT_NEAR(glm::length(s->shapes.meshes[0].positions[0] - Vec3(1, 2, 3)), 0.f, 1e-5f);
  for (const auto& w : warnings) ADD_FAILURE() << "unexpected warning: " << w;
}

// A parameter pbrt reads for some directive of the kind and this one does
// not use is a warning with its place; one that neither pbrt-v4 nor
// pbrt-v3 reads is an error, as pbrt-v4 stops on it, or with --lenient a
// warning.
TEST(Parser, UnusedAndUnsupportedThingsWarnWithTheirPlace) {
  std::vector<std::string> warnings;
  load("WorldBegin\nShape \"sphere\" \"float radius\" 1 \"float width\" 3\n"
       "MakeNamedMedium \"fog\" \"string type\" \"homogeneous\" \"float wispiness\" 1\nLightSource \"point\"\n", &warnings);
  ASSERT_EQ(warnings.size(), 2u);
  EXPECT_NE(warnings[0].find("t.pbrt:2:"), std::string::npos) << warnings[0];
  EXPECT_NE(warnings[0].find("width"), std::string::npos);
  EXPECT_NE(warnings[1].find("wispiness"), std::string::npos) << warnings[1];
  const std::string unknown = "WorldBegin\nShape \"sphere\" \"float radius\" 1 \"float wobble\" 3\n"
                              "MakeNamedMedium \"fog\" \"string type\" \"homogeneous\" \"float fluff\" 1\n";
  expect_error(unknown, {"t.pbrt:2:33", "Shape \"sphere\"", "unknown parameter \"float wobble\"", "--lenient"});
  warnings.clear();
  load(unknown, &warnings, true);
  std::erase_if(warnings, [](const std::string& w) { return w.find("--lenient") == std::string::npos; });
  ASSERT_EQ(warnings.size(), 2u);
  EXPECT_NE(warnings[0].find("t.pbrt:2:33: warning:"), std::string::npos) << warnings[0];
  EXPECT_NE(warnings[0].find("wobble"), std::string::npos) << warnings[0];
  EXPECT_NE(warnings[1].find("fluff"), std::string::npos) << warnings[1];
  // Each kind has its own names: a light's "from" is no shape's.
  expect_error("WorldBegin\nShape \"sphere\" \"point3 from\" [0 0 0]\n", {"t.pbrt:2:", "unknown parameter \"point3 from\""});
  // pbrt-v3's names are known too: dropped with a warning, not refused.
  warnings.clear();
  load("WorldBegin\nLightSource \"point\" \"integer nsamples\" 4\n", &warnings);
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_NE(warnings[0].find("nsamples"), std::string::npos) << warnings[0];
  // pbrt-v3 lets a shape carry material parameters: known, not a typo.
  warnings.clear();
  load("WorldBegin\nLightSource \"point\"\nShape \"sphere\" \"rgb Kd\" [1 0 0]\n", &warnings);
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_NE(warnings[0].find("Kd"), std::string::npos) << warnings[0];
}

// pbrt-v4's Attribute: defaults per kind for the directives that follow,
// under their own values, scoped by AttributeBegin/End; a default a
// directive does not read is no warning.
TEST(Parser, AttributesGiveDefaultsToLaterDirectives) {
  std::vector<std::string> warnings;
  auto s = load("WorldBegin\nLightSource \"point\"\nShape \"sphere\"\nAttributeBegin\n"
                "Attribute \"shape\" \"float radius\" 2 \"float innerradius\" 0\n"
                "Shape \"sphere\"\nShape \"sphere\" \"float radius\" 3\nAttribute \"shape\" \"float radius\" 4\n"
                "Shape \"sphere\"\nShape \"disk\"\nAttributeEnd\nShape \"sphere\"\n",
                &warnings);
  ASSERT_EQ(s->shapes.spheres.size(), 5u);
  const float radii[] = {1.f, 2.f, 3.f, 4.f, 1.f};
  for (size_t k = 0; k < 5; ++k) EXPECT_FLOAT_EQ(s->shapes.spheres[k].radius, radii[k]) << k;
  for (const auto& w : warnings) ADD_FAILURE() << "unexpected warning: " << w;
  expect_load_error("WorldBegin\nAttribute \"camera\" \"float fov\" 30\n", "a.pbrt", {"a.pbrt:2", "camera", "shape, light"});
  // A light's default, and an AreaLightSource's.
  s = load("WorldBegin\nAttribute \"light\" \"float scale\" 3\nLightSource \"point\"\nLightSource \"point\" \"float scale\" 2\n");
  ASSERT_EQ(s->lights.point.size(), 2u);
  EXPECT_FLOAT_EQ(s->lights.point[0].I[0], 3.f);
  EXPECT_FLOAT_EQ(s->lights.point[1].I[0], 2.f);
}

// A parameter a letter or two from one the directive wanted, or from one
// pbrt knows for its kind, is a typo: the error names the word meant.
TEST(Parser, NearMissesOfWantedParametersAreErrors) {
  expect_load_error("Camera \"perspective\" \"float fovv\" 45\n", "c.pbrt", {"c.pbrt:1", "fovv", "did you mean \"fov\""});
  expect_load_error("WorldBegin\nLightSource \"spot\" \"float coneangel\" 30\n", "l.pbrt",
                    {"l.pbrt:2", "coneangel", "\"coneangle\""});
  expect_load_error("WorldBegin\nMaterial \"conductor\" \"float roughnes\" 0.1\n", "m.pbrt", {"roughnes", "\"roughness\""});
  expect_load_error("Film \"rgb\" \"integer xresolutoin\" 64\n", "f.pbrt", {"xresolutoin", "\"xresolution\""});
  expect_load_error("WorldBegin\nShape \"sphere\" \"float phimaxx\" 90\n", "s.pbrt", {"phimaxx", "\"phimax\""});
  expect_load_error("WorldBegin\nTexture \"t\" \"float\" \"checkerboard\" \"float tex11\" 1\n", "t.pbrt",
                    {"tex11", "\"tex1\""});
  std::vector<std::string> warnings;
  load("Film \"rgb\" \"integer nbuckets\" 16 \"integer xresolution\" 8 \"integer yresolution\" 8\n"
       "Camera \"perspective\" \"float fov\" 45\nWorldBegin\n",
       &warnings);
  size_t ignored = 0;
  for (const std::string& w : warnings) ignored += w.find("is not supported and was ignored") != std::string::npos;
  EXPECT_EQ(ignored, 1u);
}

TEST(Parser, MalformedInputGivesClearErrors) {
  expect_error("WorldBegin\nFrobnicate 3\n", {"t.pbrt:2:1", "unknown directive \"Frobnicate\""});
  expect_error("WorldBegin\nShape \"sphere\" \"float radius\" [ 1 ] @\n", {"t.pbrt:2:", "unexpected characters"});
  expect_error("Include \"does-not-exist.pbrt\"\n", {"t.pbrt:1:1", "cannot open scene file"});
  expect_error("WorldBegin\nShape \"sphere\" \"float radius\" \"big\"\n", {"t.pbrt:2:", "expects numbers"});
  expect_error("WorldBegin\nShape \"sphere\" \"string radius\" \"big\"\n", {"radius", "expected \"float\""});
  expect_error("WorldBegin\nShape \"trianglemesh\" \"point3 P\" [0 0 0 1 0 0\n", {"t.pbrt:2:", "missing ']'"});
  expect_error("WorldBegin\nShape \"sphere\" \"float radius", {"t.pbrt:2:16", "unterminated string"});
  expect_error("WorldBegin\nAttributeBegin\nShape \"sphere\"\n", {"t.pbrt:2:1", "AttributeBegin without a matching AttributeEnd"});
  expect_error("WorldBegin\nAttributeEnd\n", {"t.pbrt:2:1", "without a matching"});
  expect_error("WorldBegin\nNamedMaterial \"nope\"\n", {"never defined"});
  expect_error("WorldBegin\nShape \"trianglemesh\" \"point3 P\" [0 0 0 1 0 0 0 1 0] \"integer indices\" [0 1 5]\n",
               {"t.pbrt:2:1", "out of range"});
  expect_error("WorldBegin\nShape \"trianglemesh\" \"point3 P\" [0 0 0 1 0 0 0 1 nan] \"integer indices\" [0 1 2]\n",
               {"t.pbrt:2:50", "found a directive name \"nan\""});
  expect_error("WorldBegin\nShape \"trianglemesh\" \"point3 P\" [0 0 0 1 0 0 0 1 1e39] \"integer indices\" [0 1 2]\n",
               {"Shape \"trianglemesh\"", "vertex 2 at (0, 1, inf) is not finite"});
  expect_error("WorldBegin\nShape \"cone\"\n", {"shape \"cone\" is not supported"});
  expect_error("WorldBegin\nMaterial \"measured\" \"string filename\" \"x.bsdf\"\n", {"t.pbrt:2", "x.bsdf: cannot open the tabulated BSDF file"});
  expect_error("WorldBegin\nCamera \"perspective\"\n", {"only allowed before WorldBegin"});
  expect_error("Camera \"fisheye\"\n", {"camera type \"fisheye\" is not supported"});
  expect_error("WorldBegin\nScale -1 0 1\nShape \"sphere\"\n", {"t.pbrt:3", "transform is singular"});
  expect_error("WorldBegin\nShape \"sphere\" \"float radius\" 1 \"float radius\" 2\n", {"given twice"});
  expect_error("WorldBegin\nShape \"plymesh\" \"string filename\" \"missing.ply\"\n", {"missing.ply", "cannot open PLY"});
}

TEST(Parser, IncludeCyclesAreReported) {
  auto dir = std::filesystem::temp_directory_path() / "lantern-parser-test";
  std::filesystem::create_directories(dir);
  std::ofstream(dir / "a.pbrt") << "Include \"b.pbrt\"\n";
  std::ofstream(dir / "b.pbrt") << "\n\nInclude \"a.pbrt\"\n";
  try {
    load_scene((dir / "a.pbrt").string());
    ADD_FAILURE() << "cycle not detected";
  } catch (const InputError& e) {
    std::string msg = e.what();
    EXPECT_NE(msg.find("b.pbrt:3:1"), std::string::npos) << msg;
    EXPECT_NE(msg.find("Include cycle"), std::string::npos) << msg;
  }
}

TEST(Parser, DeepNestingIsBounded) {
  std::string s = "WorldBegin\n";
  for (int i = 0; i < 20000; ++i) s += "AttributeBegin\n";
  expect_error(s, {"t.pbrt:10002:1", "nested deeper than 10000"});
}

// PLY meshes are read in parallel after parsing; what they report must not
// depend on thread timing: the first bad mesh in file order is named, and
// an empty one is skipped with a warning at its own line.
TEST(Parser, ParallelPlyReadsReportInFileOrder) {
  const std::string dir = ::testing::TempDir();
  auto write = [&](const std::string& name, const std::string& body) { std::ofstream(dir + "/" + name) << body; };
  const std::string head = "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n";
  write("good.ply", head + "element face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0 1 0 0 0 1 0 3 0 1 2\n");
  write("empty.ply", head + "element face 0\nproperty list uchar int vertex_indices\nend_header\n0 0 0 1 0 0 0 1 0\n");
  write("bad1.ply", head + "element face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0 1 0 0 0 1 0 3 0 1 9\n");
  write("bad2.ply", "plx\n");
  auto shapes = [&](std::initializer_list<const char*> files) {
    std::string s = "WorldBegin\n";
    for (const char* f : files) s += std::string("Shape \"plymesh\" \"string filename\" \"") + dir + "/" + f + "\"\n";
    return s;
  };
  for (int round = 0; round < 5; ++round) {
    expect_error(shapes({"good.ply", "good.ply", "bad1.ply", "good.ply", "bad2.ply"}), {"bad1.ply: error: PLY", "vertex 9"});
    expect_error(shapes({"bad2.ply", "bad1.ply"}), {"bad2.ply", "does not start with \"ply\""});
  }
  std::vector<std::string> warnings;
  auto scene = load(shapes({"good.ply", "empty.ply", "good.ply"}), &warnings);
  EXPECT_EQ(scene_info(*scene).triangles, 2u);
  bool warned = false;
  for (const std::string& w : warnings) warned = warned || (w.find("t.pbrt:3:1") != std::string::npos && w.find("no triangles") != std::string::npos);
  EXPECT_TRUE(warned);
}

// Binary garbage, mis-encoded text and megabyte tokens: a message that is
// short, printable, and still points at the place.
TEST(Parser, HostileBytesGiveShortPrintableErrors) {
  auto message = [](const std::string& text) -> std::string {
    try {
      load(text);
    } catch (const InputError& e) {
      return e.what();
    }
    return "(no error)";
  };
  auto printable = [](const std::string& m) {
    for (unsigned char c : m)
      if (c < 0x20 || c >= 0x7f) return false;
    return true;
  };
  std::string latin1 = message("WorldBegin\nSh\xe9pe \"sphere\"\n");  // not UTF-8
  EXPECT_NE(latin1.find("t.pbrt:2:1"), std::string::npos) << latin1;
  EXPECT_NE(latin1.find("Sh\\xe9pe"), std::string::npos) << latin1;
  EXPECT_TRUE(printable(latin1)) << latin1;
  std::string nul = message(std::string("WorldBegin\n\0\x01\xff", 14));
  EXPECT_TRUE(printable(nul)) << nul;
  EXPECT_NE(nul.find("t.pbrt:2:1"), std::string::npos) << nul;
  // Appended, not concatenated: GCC 12 misreads the latter as an overflow.
  std::string huge_input = "WorldBegin\n";
  huge_input.append(size_t(4) << 20, 'A').append("\n");
  std::string huge = message(huge_input);
  EXPECT_NE(huge.find("unknown directive"), std::string::npos) << huge.substr(0, 200);
  EXPECT_LT(huge.size(), 200u);
  std::string long_input = "WorldBegin\nShape \"";
  long_input.append(size_t(4) << 20, 'x').append("\"\n");
  std::string long_string = message(long_input);
  EXPECT_LT(long_string.size(), 300u);
  // Special files are refused, not read forever.
  EXPECT_NE(message("Include \"/dev/zero\"\n").find("not a regular file"), std::string::npos);
  EXPECT_NE(message("WorldBegin\nShape \"plymesh\" \"string filename\" \"/dev/zero\"\n").find("not a regular file"),
            std::string::npos);
}

// pbrt-v4 looks the camera's medium up at the Camera, so a medium named
// after it stops pbrt-v4; Lantern renders such a file and says so.
TEST(Parser, ACameraMediumNamedAfterTheCameraWarnsThatPbrtV4RefusesIt) {
  const std::string medium = "MakeNamedMedium \"fog\" \"string type\" \"homogeneous\"\n";
  const std::string camera = "MediumInterface \"\" \"fog\"\nCamera \"perspective\"\n";
  std::vector<std::string> warnings;
  auto refusals = [&warnings] {  // (the scene's want of lights is a warning too)
    std::erase_if(warnings, [](const std::string& w) { return w.find("pbrt-v4 refuses") == std::string::npos; });
    return warnings;
  };
  auto late = load(camera + "WorldBegin\n" + medium, &warnings);
  EXPECT_FALSE(late->media.camera.vacuum());
  ASSERT_EQ(refusals().size(), 1u);
  EXPECT_NE(warnings[0].find("t.pbrt:1:"), std::string::npos) << warnings[0];
  EXPECT_NE(warnings[0].find("\"fog\""), std::string::npos) << warnings[0];
  warnings.clear();
  auto early = load(medium + camera + "WorldBegin\n", &warnings);
  EXPECT_FALSE(early->media.camera.vacuum());
  EXPECT_TRUE(refusals().empty()) << warnings[0];
}

}  // namespace
}  // namespace lantern
