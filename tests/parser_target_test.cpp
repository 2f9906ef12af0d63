// The pbrt parser drives a ParserTarget and nothing else: a recording target
// sees each directive with its parameters and composed transformations,
// and a scene built by calling SceneBuilder through that interface, with
// no pbrt text, renders the image the same scene's text renders.
#include <gtest/gtest.h>

#include <cstring>

#include "lantern/render.h"
#include "scene/builder.h"
#include "scene/pbrt/parser.h"
#include "same_image.h"

namespace lantern {
namespace {

// Records what the parser hands over.
class Recorder final : public pbrt::ParserTarget {
 public:
  std::vector<std::string> calls;
  mutable std::vector<std::string> warnings;
  Mat4 light_ctm{1.f};
  std::string light_medium, camera_medium_name;

  void warn(const SourceLocation&, const std::string& what) const override { warnings.push_back(what); }
  void warn_line(const std::string& line) const override { warnings.push_back(line); }
  void camera(const std::string& type, const pbrt::ParamSet&, const glm::dmat4&, const glm::dmat4&) override {
    calls.push_back("camera " + type);
  }
  void camera_medium(const std::string& name, const SourceLocation&) override { camera_medium_name = name; }
  void film(const std::string& type, const pbrt::ParamSet& ps) override {
    calls.push_back("film " + type + " " + std::to_string(ps.get_int("xresolution", 0)));
  }
  void sampler(const std::string& type, const pbrt::ParamSet&) override { calls.push_back("sampler " + type); }
  void integrator(const std::string& type, const pbrt::ParamSet&) override { calls.push_back("integrator " + type); }
  void pixel_filter(const std::string& type, const pbrt::ParamSet&) override { calls.push_back("filter " + type); }
  void begin_world(const glm::dmat4&, double, double) override { calls.push_back("world"); }
  MaterialHandle material(const std::string& type, const pbrt::ParamSet&, const std::map<std::string, MaterialHandle>& named,
                          const std::string&) override {
    calls.push_back("material " + type + " (" + std::to_string(named.size()) + " named)");
    return MaterialHandle::make(MaterialKind::Diffuse, uint32_t(calls.size()));
  }
  void texture(const std::string& name, const std::string& value_type, const std::string& cls, const pbrt::ParamSet&,
               const Mat4&, const std::string&) override {
    calls.push_back("texture " + name + " " + value_type + " " + cls);
  }
  void shape(const std::string& type, const pbrt::ParamSet&, const GraphicsState& gs, const std::string&) override {
    calls.push_back("shape " + type + (gs.material ? " with material" : ""));
  }
  void light(const std::string& type, const pbrt::ParamSet&, const Mat4& ctm, const std::string&,
             const std::string& medium, const SourceLocation&) override {
    calls.push_back("light " + type);
    light_ctm = ctm;
    light_medium = medium;
  }
  void medium(const std::string& name, const pbrt::ParamSet&, const Mat4&, const std::string&) override {
    calls.push_back("medium " + name);
  }
  void begin_object(const std::string& name, const SourceLocation&) override { calls.push_back("object " + name); }
  void end_object(const SourceLocation&) override { calls.push_back("end object"); }
  void object_instance(const std::string& name, const glm::dmat4&, const glm::dmat4&, const SourceLocation&) override {
    calls.push_back("instance " + name);
  }
};

TEST(ParserTarget, TheParserHandsEachDirectiveToItsTarget) {
  Recorder r;
  pbrt::parse_string(R"(Film "rgb" "integer xresolution" 32 "integer yresolution" 24
LookAt 0 0 -5  0 0 0  0 1 0
Camera "perspective"
Sampler "independent"
WorldBegin
MakeNamedMedium "fog" "string type" "homogeneous"
MediumInterface "" "fog"
AttributeBegin
  Translate 1 2 3
  LightSource "point" "rgb I" [1 1 1]
AttributeEnd
Texture "checks" "spectrum" "checkerboard"
MakeNamedMaterial "white" "string type" "diffuse"
NamedMaterial "white"
Translate 0 0 2
Shape "sphere"
ObjectBegin "thing"
Shape "sphere"
ObjectEnd
ObjectInstance "thing"
)",
                     "recorded.pbrt", ".", r);
  const std::vector<std::string> expected = {
      "film rgb 32", "camera perspective", "sampler independent", "world", "medium fog", "light point",
      "texture checks spectrum checkerboard", "material diffuse (0 named)", "shape sphere with material",
      "object thing", "shape sphere with material", "end object", "instance thing"};
  EXPECT_EQ(r.calls, expected);
  EXPECT_EQ(r.light_medium, "fog") << "a light emits into the graphics state's outside medium";
  EXPECT_FLOAT_EQ(r.light_ctm[3][1], 2.f) << "the light's transformation, composed";
  // (what a target does not read, the parser reports as unused)
  EXPECT_FALSE(r.warnings.empty());
}

pbrt::Param param(const std::string& type, const std::string& name, std::vector<double> numbers) {
  pbrt::Param p;
  p.type = type;
  p.name = name;
  p.numbers = std::move(numbers);
  return p;
}

// A floor lit by a quad light, built in code through the target: the
// camera at the origin (so render space is world space), looking along z.
void build_in_code(pbrt::ParserTarget& t) {
  pbrt::ParamSet film;
  film.params = {param("integer", "xresolution", {32}), param("integer", "yresolution", {24})};
  t.film("rgb", film);
  pbrt::ParamSet camera;
  camera.params = {param("float", "fov", {50})};
  t.camera("perspective", camera, glm::dmat4(1.0), glm::dmat4(1.0));
  t.camera_medium("", SourceLocation{});
  t.begin_world(glm::dmat4(1.0), 0.0, 1.0);
  pbrt::ParamSet matte;
  matte.params = {param("rgb", "reflectance", {0.7, 0.5, 0.3})};
  GraphicsState gs;
  gs.material = t.material("diffuse", matte, {}, ".");
  pbrt::ParamSet floor;
  floor.params = {param("point3", "P", {-2, -1, 1, 2, -1, 1, 2, -1, 5, -2, -1, 5}),
                  param("integer", "indices", {0, 1, 2, 0, 2, 3})};
  t.shape("trianglemesh", floor, gs, ".");
  pbrt::ParamSet area;
  pbrt::Param two_sided;
  two_sided.type = "bool";
  two_sided.name = "twosided";
  two_sided.bools = {true};
  area.params = {param("rgb", "L", {4, 4, 4}), two_sided};
  gs.area_light = area;
  pbrt::ParamSet lamp;
  lamp.params = {param("point3", "P", {-0.5, 0.5, 2.5, -0.5, 0.5, 3.5, 0.5, 0.5, 3.5, 0.5, 0.5, 2.5}),
                 param("integer", "indices", {0, 1, 2, 0, 2, 3})};
  t.shape("trianglemesh", lamp, gs, ".");
}

TEST(ParserTarget, ASceneBuiltInCodeRendersAsItsText) {
  const char* text = R"(Film "rgb" "integer xresolution" 32 "integer yresolution" 24
Camera "perspective" "float fov" 50
WorldBegin
Material "diffuse" "rgb reflectance" [0.7 0.5 0.3]
Shape "trianglemesh" "point3 P" [-2 -1 1  2 -1 1  2 -1 5  -2 -1 5] "integer indices" [0 1 2 0 2 3]
AreaLightSource "diffuse" "rgb L" [4 4 4] "bool twosided" true
Shape "trianglemesh" "point3 P" [-0.5 0.5 2.5  -0.5 0.5 3.5  0.5 0.5 3.5  0.5 0.5 2.5] "integer indices" [0 1 2 0 2 3]
)";
  auto from_text = load_scene_from_string(text, "floor.pbrt");
  auto in_code = std::make_shared<Scene>();
  {
    SceneBuilder b(*in_code, nullptr);
    build_in_code(b);
    b.finish();
  }
  RenderOptions o;
  o.spp = 8;
  o.seed = 5;
  const Image a = render(*from_text, o).image, b = render(*in_code, o).image;
  ASSERT_EQ(a.width, 32);
  double sum = 0;
  for (float v : a.rgb) sum += v;
  EXPECT_GT(sum, 0.0) << "the floor is lit";
  EXPECT_TRUE(same_image(a, b)) << "the scene built in code differs from its text";
}

}  // namespace
}  // namespace lantern
