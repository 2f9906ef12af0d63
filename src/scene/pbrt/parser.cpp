#include "scene/pbrt/parser.h"

#include <algorithm>
#include <array>
#include <tuple>
#include <charconv>
#include <filesystem>
#include <glm/gtc/matrix_transform.hpp>
#include <map>

#include "math/motion.h"
#include "scene/pbrt/tokenizer.h"

namespace lantern::pbrt {

namespace {

constexpr size_t kMaxIncludeDepth = 64;
constexpr size_t kMaxAttributeDepth = 10000;

class Parser {
 public:
  Parser(ParserTarget& b, std::string base_dir) : b_(b), base_dir_(std::move(base_dir)) {}

  void run(std::unique_ptr<Tokenizer> root) {
    files_.push_back(std::move(root));
    for (;;) {
      Token t = next();
      if (t.kind == TokenKind::End) break;
      if (t.kind != TokenKind::Identifier) fail(t, std::string("expected a directive name, found ") + token_kind_name(t.kind) + describe(t));
      directive(t);
    }
    if (!stack_.empty()) throw InputError(stack_where_.back(), "AttributeBegin without a matching AttributeEnd");
  }

 private:
  // --- tokens ------------------------------------------------------------
  Token next() {
    if (peeked_) {
      Token t = *peeked_;
      peeked_.reset();
      return t;
    }
    while (!files_.empty()) {
      Token t = files_.back()->next();
      if (t.kind != TokenKind::End) {
        current_ = files_.back().get();
        return t;
      }
      if (files_.size() == 1) {
        current_ = files_.back().get();
        return t;
      }
      files_.pop_back();
    }
    return Token{};
  }
  Token peek() {
    if (!peeked_) peeked_ = next();
    return *peeked_;
  }
  SourceLocation loc(const Token& t) const { return current_->location(t); }
  [[noreturn]] void fail(const Token& t, const std::string& what) const { throw InputError(loc(t), what); }
  static std::string describe(const Token& t) {
    if (t.kind == TokenKind::End) return "";
    return " \"" + printable(t.text) + "\"";
  }

  std::string expect_string(const char* what) {
    Token t = next();
    if (t.kind != TokenKind::String)
      fail(t, std::string("expected ") + what + " (a quoted string), found " + token_kind_name(t.kind) + describe(t));
    return unescape(t.text);
  }
  double to_number(const Token& t) {
    double v = 0.0;
    const char* b = t.text.data();
    const char* e = b + t.text.size();
    if (*b == '+') ++b;
    auto [ptr, ec] = std::from_chars(b, e, v);
    if (ec != std::errc() || ptr != e) fail(t, "malformed number" + describe(t));
    return v;
  }
  std::vector<double> numbers(size_t n, const char* what) {
    std::vector<double> v;
    Token t = peek();
    bool bracket = t.kind == TokenKind::OpenBracket;
    if (bracket) next();
    for (size_t i = 0; i < n; ++i) {
      Token x = next();
      if (x.kind != TokenKind::Number)
        fail(x, std::string(what) + " expects " + std::to_string(n) + " numbers; found " + token_kind_name(x.kind) + describe(x));
      v.push_back(to_number(x));
    }
    if (bracket) {
      Token c = next();
      if (c.kind != TokenKind::CloseBracket) fail(c, std::string(what) + ": expected ']' after " + std::to_string(n) + " numbers");
    }
    return v;
  }

  // --- parameter lists ---------------------------------------------------
  // The directive's parameters, then the defaults an Attribute gave for
  // its kind (`attributes`: "shape", "light", ...) where it gives none of
  // the same name. The defaults count as used: as in pbrt-v4, one that a
  // directive does not read is no warning.
  // kind: the directive's (pbrt/known_params.h).
  ParamSet params(const Token& at, const std::string& directive, const char* kind, const char* attributes = nullptr) {
    ParamSet ps = own_params(at, directive);
    ps.kind = kind;
    if (!attributes) return ps;
    auto it = gs_.attributes.find(attributes);
    if (it == gs_.attributes.end()) return ps;
    for (const Param& a : it->second)
      if (std::none_of(ps.params.begin(), ps.params.end(), [&](const Param& p) { return p.name == a.name; })) {
        ps.params.push_back(a);
        ps.params.back().used = true;
      }
    return ps;
  }
  ParamSet own_params(const Token& at, const std::string& directive) {
    ParamSet ps;
    ps.where = loc(at);
    ps.directive = directive;
    ps.base_dir = base_dir_;
    ps.warn = &warn_sink_;
    ps.lenient = b_.lenient();
    ps.color_space = gs_.color_space;
    while (peek().kind == TokenKind::String) {
      Token decl = next();
      Param p;
      p.where = loc(decl);
      std::string s = unescape(decl.text);
      size_t a = s.find_first_not_of(" \t"), sp = s.find_first_of(" \t", a);
      size_t c = sp == std::string::npos ? sp : s.find_first_not_of(" \t", sp);
      if (a == std::string::npos || c == std::string::npos)
        fail(decl, "expected a parameter declaration \"type name\", found \"" + printable(s) + "\"");
      p.type = s.substr(a, sp - a);
      p.name = s.substr(c, s.find_last_not_of(" \t") - c + 1);
      static const char* kTypes[] = {"integer", "float",  "point2", "vector2", "point3",    "vector3", "normal",
                                     "normal3", "point",  "vector", "color",   "rgb",       "spectrum", "blackbody",
                                     "bool",    "string", "texture"};
      bool known = false;
      for (const char* k : kTypes) known |= p.type == k;
      if (!known) fail(decl, "unknown parameter type \"" + p.type + "\" in \"" + printable(s) + "\"");
      values(p, decl);
      for (const Param& q : ps.params)
        if (q.name == p.name) fail(decl, "parameter \"" + printable(p.name) + "\" is given twice");
      ps.params.push_back(std::move(p));
    }
    return ps;
  }

  void value(Param& p, const Token& v) {
    bool stringy = p.type == "string" || p.type == "texture" || p.type == "bool" || p.type == "spectrum";
    if (v.kind == TokenKind::Number) {
      if (p.type == "string" || p.type == "texture" || p.type == "bool")
        fail(v, "parameter \"" + printable(p.name) + "\" of type \"" + p.type + "\" expects quoted strings, found a number");
      p.numbers.push_back(to_number(v));
    } else if (v.kind == TokenKind::String || (p.type == "bool" && v.kind == TokenKind::Identifier)) {
      if (!stringy) fail(v, "parameter \"" + printable(p.name) + "\" of type \"" + p.type + "\" expects numbers, found a string" + describe(v));
      std::string s = unescape(v.text);
      if (p.type == "bool") {
        if (s != "true" && s != "false") fail(v, "parameter \"" + printable(p.name) + "\" expects true or false, found \"" + printable(s) + "\"");
        p.bools.push_back(s == "true");
      } else {
        p.strings.push_back(std::move(s));
      }
    } else {
      fail(v, "expected a value for parameter \"" + printable(p.name) + "\", found " + token_kind_name(v.kind) + describe(v));
    }
  }

  void values(Param& p, const Token& decl) {
    Token t = next();
    if (t.kind != TokenKind::OpenBracket) {
      value(p, t);
      return;
    }
    for (;;) {
      Token v = next();
      if (v.kind == TokenKind::CloseBracket) break;
      if (v.kind == TokenKind::End) fail(decl, "the file ended inside the value list of \"" + printable(p.name) + "\" (missing ']')");
      value(p, v);
    }
  }

  // --- directives --------------------------------------------------------
  void directive(const Token& t) {
    const std::string_view d = t.text;
    auto world_only = [&] {
      if (!in_world_) fail(t, std::string(d) + " is only allowed after WorldBegin");
    };
    auto options_only = [&] {
      if (in_world_) fail(t, std::string(d) + " is only allowed before WorldBegin");
    };
    // pbrt's two current transformations, at the start and the end of the
    // motion; ActiveTransform chooses which the directives change.
    glm::dmat4& ctm = gs_.world_from_object;
    auto apply = [&](auto&& f) {
      if (gs_.active_transforms & 1) gs_.world_from_object = f(gs_.world_from_object);
      if (gs_.active_transforms & 2) gs_.world_from_object_end = f(gs_.world_from_object_end);
    };
    if (d == "Translate") {
      auto v = numbers(3, "Translate");
      apply([&](const glm::dmat4& m) { return glm::translate(m, glm::dvec3(v[0], v[1], v[2])); });
    } else if (d == "Scale") {
      auto v = numbers(3, "Scale");
      apply([&](const glm::dmat4& m) { return glm::scale(m, glm::dvec3(v[0], v[1], v[2])); });
    } else if (d == "Rotate") {
      auto v = numbers(4, "Rotate");
      glm::dvec3 axis{v[1], v[2], v[3]};
      if (glm::length(axis) == 0.0) fail(t, "Rotate: the axis must not be zero");
      apply([&](const glm::dmat4& m) { return glm::rotate(m, glm::radians(v[0]), glm::normalize(axis)); });
    } else if (d == "LookAt") {
      auto v = numbers(9, "LookAt");
      const glm::dmat4 l = look_at(t, glm::dvec3(v[0], v[1], v[2]), glm::dvec3(v[3], v[4], v[5]), glm::dvec3(v[6], v[7], v[8]));
      apply([&](const glm::dmat4& m) { return m * l; });
    } else if (d == "Transform" || d == "ConcatTransform") {
      auto v = numbers(16, std::string(d).c_str());
      glm::dmat4 n;
      for (int i = 0; i < 16; ++i) n[i / 4][i % 4] = v[size_t(i)];
      apply([&](const glm::dmat4& m) { return d == "Transform" ? n : m * n; });
    } else if (d == "Identity") {
      apply([](const glm::dmat4&) { return glm::dmat4(1.0); });
    } else if (d == "CoordinateSystem") {
      named_cs_[expect_string("a coordinate system name")] = {gs_.world_from_object, gs_.world_from_object_end};
    } else if (d == "CoordSysTransform") {
      std::string n = expect_string("a coordinate system name");
      auto it = named_cs_.find(n);
      if (it == named_cs_.end()) b_.warn(loc(t), "unknown coordinate system \"" + printable(n) + "\" ignored");
      else std::tie(gs_.world_from_object, gs_.world_from_object_end) = it->second;
    } else if (d == "ActiveTransform") {
      const Token which = next();
      if (which.kind != TokenKind::Identifier || (which.text != "StartTime" && which.text != "EndTime" && which.text != "All"))
        fail(which, "ActiveTransform expects StartTime, EndTime or All" + describe(which));
      gs_.active_transforms = which.text == "StartTime" ? 1 : which.text == "EndTime" ? 2 : 3;
    } else if (d == "TransformTimes") {
      options_only();
      auto v = numbers(2, "TransformTimes");
      if (!(v[1] >= v[0])) fail(t, "TransformTimes: the end time must not come before the start time");
      if (camera_from_world_[0] != camera_from_world_[1] && (v[0] != transform_times_[0] || v[1] != transform_times_[1]))
        fail(t, "TransformTimes after a moving Camera: give the times before the Camera");
      transform_times_ = {v[0], v[1]};
    } else if (d == "ReverseOrientation") {
      gs_.reverse_orientation = !gs_.reverse_orientation;
    } else if (d == "AttributeBegin" || d == "TransformBegin") {
      if (stack_.size() >= kMaxAttributeDepth) fail(t, "AttributeBegin nested deeper than " + std::to_string(kMaxAttributeDepth));
      stack_.push_back(gs_);
      stack_where_.push_back(loc(t));
      transform_only_.push_back(d == "TransformBegin");
    } else if (d == "AttributeEnd" || d == "TransformEnd") {
      if (stack_.empty()) fail(t, std::string(d) + " without a matching " + (d == "AttributeEnd" ? "AttributeBegin" : "TransformBegin"));
      if (!object_depth_.empty() && object_depth_.back() == stack_.size())
        fail(t, std::string(d) + " would close an ObjectBegin; close it with ObjectEnd");
      if (transform_only_.back()) {
        gs_.world_from_object = stack_.back().world_from_object;
        gs_.world_from_object_end = stack_.back().world_from_object_end;
        gs_.active_transforms = stack_.back().active_transforms;
      } else {
        gs_ = stack_.back();
      }
      stack_.pop_back();
      stack_where_.pop_back();
      transform_only_.pop_back();
    } else if (d == "WorldBegin") {
      options_only();
      in_world_ = true;
      ctm = gs_.world_from_object_end = glm::dmat4(1.0);
      gs_.active_transforms = 3;
      named_cs_["world"] = {ctm, ctm};
      render_from_world_ = render_from_world();
      b_.begin_world(render_from_world_, transform_times_[0], transform_times_[1]);
    } else if (d == "WorldEnd") {
      world_only();
    } else if (d == "Camera") {
      options_only();
      std::string type = expect_string("a camera type");
      ParamSet ps = params(t, "Camera \"" + printable(type) + "\"", "camera");
      b_.camera(type, ps, ctm, gs_.world_from_object_end);
      b_.camera_medium(gs_.outside_medium, gs_.medium_where);
      camera_from_world_ = {ctm, gs_.world_from_object_end};
      named_cs_["camera"] = {glm::inverse(ctm), glm::inverse(gs_.world_from_object_end)};
      ps.warn_unused();
    } else if (d == "ColorSpace") {
      // Graphics state, as in pbrt-v4: allowed anywhere, scoped by
      // AttributeBegin/End.
      const std::string name = expect_string("a colour space name");
      gs_.color_space = ColorSpace::named(name);
      if (!gs_.color_space)
        fail(t, "ColorSpace \"" + printable(name) + "\" is unknown; expected srgb, rec2020, dci-p3 or aces2065-1");
    } else if (d == "Film" || d == "Sampler" || d == "Integrator" || d == "PixelFilter" || d == "Accelerator" ||
               d == "Option") {
      options_only();
      std::string type = expect_string("a type name");
      if (d == "Option") {
        option(t, type);
        return;
      }
      const char* kind = d == "Film" ? "film" : d == "Sampler" ? "sampler" : d == "Integrator" ? "integrator"
                       : d == "PixelFilter" ? "filter" : "accelerator";
      ParamSet ps = params(t, std::string(d) + " \"" + printable(type) + "\"", kind);
      if (d == "Film") b_.film(type, ps);
      else if (d == "Sampler") b_.sampler(type, ps);
      else if (d == "Integrator") b_.integrator(type, ps);
      else if (d == "PixelFilter") b_.pixel_filter(type, ps);
      if (d != "Accelerator") ps.warn_unused();
    } else if (d == "Include" || d == "Import") {
      include(t, expect_string("a file name"));
    } else if (d == "Material") {
      world_only();
      std::string type = expect_string("a material type");
      ParamSet ps = params(t, "Material \"" + printable(type) + "\"", "material", "material");
      gs_.material = b_.material(type, ps, named_materials_, base_dir_);
      ps.warn_unused();
    } else if (d == "MakeNamedMaterial") {
      world_only();
      std::string name = expect_string("a material name");
      ParamSet ps = params(t, "MakeNamedMaterial \"" + printable(name) + "\"", "material", "material");
      std::string type = ps.get_string("type", "");
      if (type.empty()) ps.fail("needs a \"string type\" parameter");
      if (named_materials_.count(name)) b_.warn(loc(t), "material \"" + printable(name) + "\" redefined");
      named_materials_[name] = b_.material(type, ps, named_materials_, base_dir_);
      ps.warn_unused();
    } else if (d == "NamedMaterial") {
      world_only();
      std::string name = expect_string("a material name");
      auto it = named_materials_.find(name);
      if (it == named_materials_.end()) fail(t, "NamedMaterial \"" + printable(name) + "\" was never defined with MakeNamedMaterial");
      gs_.material = it->second;
    } else if (d == "Texture") {
      world_only();
      std::string name = expect_string("a texture name");
      std::string vtype = expect_string("a texture value type");
      std::string cls = expect_string("a texture class");
      ParamSet ps = params(t, "Texture \"" + printable(name) + "\"", "texture", "texture");
      still("texture", t);
      b_.texture(name, vtype, cls, ps, render(ctm), base_dir_);
      ps.warn_unused();
    } else if (d == "LightSource") {
      world_only();
      std::string type = expect_string("a light type");
      ParamSet ps = params(t, "LightSource \"" + printable(type) + "\"", "light", "light");
      still("light", t);
      b_.light(type, ps, render(ctm), base_dir_, gs_.outside_medium, gs_.medium_where);
      ps.warn_unused();
    } else if (d == "AreaLightSource") {
      world_only();
      std::string type = expect_string("an area light type");
      ParamSet ps = params(t, "AreaLightSource \"" + printable(type) + "\"", "arealight", "light");
      // pbrt-v3 calls the diffuse area light "area".
      if (type != "diffuse" && type != "area")
        ps.fail("area light type \"" + printable(type) + "\" is not supported; expected \"diffuse\" (pbrt-v3: \"area\")");
      gs_.area_light = std::move(ps);
      gs_.area_light_dir = base_dir_;
    } else if (d == "Shape") {
      world_only();
      std::string type = expect_string("a shape type");
      ParamSet ps = params(t, "Shape \"" + printable(type) + "\"", "shape", "shape");
      gs_.render_from_object = render_from_world_ * ctm;
      gs_.render_from_object_end = render_from_world_ * gs_.world_from_object_end;
      b_.shape(type, ps, gs_, base_dir_);
      ps.warn_unused();
    } else if (d == "MediumInterface") {
      // One name sets both sides, as in pbrt.
      gs_.inside_medium = expect_string("a medium name");
      gs_.outside_medium = peek().kind == TokenKind::String ? expect_string("a medium name") : gs_.inside_medium;
      gs_.medium_where = loc(t);
    } else if (d == "MakeNamedMedium") {
      std::string name = expect_string("a medium name");
      ParamSet ps = params(t, "MakeNamedMedium \"" + printable(name) + "\"", "medium", "medium");
      still("medium", t);
      b_.medium(name, ps, render(ctm), base_dir_);
      ps.warn_unused();
    } else if (d == "Attribute") {
      // Defaults for the kind's later directives, in the graphics state: a
      // later Attribute's value of the same name replaces an earlier one.
      const std::string kind = expect_string("an attribute target: shape, light, material, medium or texture");
      if (kind != "shape" && kind != "light" && kind != "material" && kind != "medium" && kind != "texture")
        fail(t, "Attribute \"" + printable(kind) + "\" is unknown; expected shape, light, material, medium or texture");
      std::vector<Param>& defaults = gs_.attributes[kind];
      for (Param& p : own_params(t, "Attribute \"" + kind + "\"").params) {
        auto same = std::find_if(defaults.begin(), defaults.end(), [&](const Param& q) { return q.name == p.name; });
        if (same != defaults.end()) *same = std::move(p);
        else defaults.push_back(std::move(p));
      }
    } else if (d == "ObjectBegin") {
      // As in pbrt: an object's shapes keep the transform current at their
      // definition, and ObjectBegin/End also push and pop the attributes.
      world_only();
      std::string name = expect_string("an object name");
      if (stack_.size() >= kMaxAttributeDepth) fail(t, "AttributeBegin nested deeper than " + std::to_string(kMaxAttributeDepth));
      b_.begin_object(name, loc(t));
      stack_.push_back(gs_);
      stack_where_.push_back(loc(t));
      transform_only_.push_back(false);
      object_depth_.push_back(stack_.size());
    } else if (d == "ObjectEnd") {
      world_only();
      if (object_depth_.empty()) fail(t, "ObjectEnd without ObjectBegin");
      if (object_depth_.back() != stack_.size())
        fail(t, "ObjectEnd does not close the innermost ObjectBegin (an AttributeBegin inside it is still open?)");
      b_.end_object(loc(t));
      gs_ = stack_.back();
      stack_.pop_back();
      stack_where_.pop_back();
      transform_only_.pop_back();
      object_depth_.pop_back();
    } else if (d == "ObjectInstance") {
      world_only();
      std::string name = expect_string("an object name");
      // Objects are stored in render space as defined; an instance places
      // its render-space copy: render_from_world M world_from_render.
      const glm::dmat4 world_from_render = glm::inverse(render_from_world_);
      b_.object_instance(name, render_from_world_ * ctm * world_from_render,
                         render_from_world_ * gs_.world_from_object_end * world_from_render, loc(t));
    } else {
      fail(t, "unknown directive \"" + printable(d) + "\"");
    }
  }

  void values_skip() {
    next();
    for (Token v = next(); v.kind != TokenKind::CloseBracket; v = next())
      if (v.kind == TokenKind::End) fail(v, "the file ended inside a value list (missing ']')");
  }

  // pbrt's LookAt: the camera-from-world matrix of a left-handed camera.
  glm::dmat4 look_at(const Token& t, glm::dvec3 pos, glm::dvec3 look, glm::dvec3 up) {
    glm::dvec3 dir = look - pos;
    if (glm::length(dir) == 0.0) fail(t, "LookAt: eye and look-at point coincide");
    dir = glm::normalize(dir);
    glm::dvec3 right = glm::cross(glm::normalize(up), dir);
    if (glm::length(right) == 0.0) fail(t, "LookAt: the up vector is parallel to the viewing direction");
    right = glm::normalize(right);
    glm::dvec3 new_up = glm::cross(dir, right);
    glm::dmat4 world_from_camera(glm::dvec4(right, 0.0), glm::dvec4(new_up, 0.0), glm::dvec4(dir, 0.0),
                                 glm::dvec4(pos, 1.0));
    return glm::inverse(world_from_camera);
  }

  // The space shapes, lights and the camera are stored in, as pbrt-v4's
  // Option "renderingcoordinatesystem": "cameraworld" (the default: the
  // world's axes, the camera at the origin), "camera", or "world". Composed
  // in double precision, so coordinates stay small near the camera
  // however far from the world's origin the scene lies.
  // A moving camera's space is taken halfway through its motion, as
  // pbrt-v4 takes it.
  glm::dmat4 render_from_world() const {
    if (rendering_space_ == "world") return glm::dmat4(1.0);
    glm::dmat4 world_from_camera = glm::inverse(camera_from_world_[0]);
    if (camera_from_world_[0] != camera_from_world_[1])
      world_from_camera = interpolate_transform(world_from_camera, glm::inverse(camera_from_world_[1]), 0.5);
    if (rendering_space_ == "camera") return glm::inverse(world_from_camera);
    return glm::translate(glm::dmat4(1.0), -glm::dvec3(world_from_camera[3]));
  }
  // pbrt-v4 gives lights, textures and media the transform at the start
  // of the motion, with a warning when it moves.
  void still(const char* what, const Token& t) const {
    if (gs_.world_from_object != gs_.world_from_object_end)
      b_.warn(loc(t), std::string("a moving ") + what + " is not supported (nor in pbrt-v4); it stays where the motion starts");
  }
  Mat4 render(const glm::dmat4& world_from_object) const { return Mat4(render_from_world_ * world_from_object); }

  // Option "type name" value: renderingcoordinatesystem is read; the
  // others warn.
  void option(const Token& t, const std::string& decl) {
    const bool bracket = peek().kind == TokenKind::OpenBracket;
    if (decl == "string renderingcoordinatesystem") {
      if (bracket) next();
      std::string v = expect_string("a coordinate system: cameraworld, camera or world");
      if (bracket && next().kind != TokenKind::CloseBracket) fail(t, "Option: expected ']' after the value");
      if (v != "cameraworld" && v != "camera" && v != "world")
        fail(t, "Option renderingcoordinatesystem \"" + printable(v) + "\" is unknown; expected cameraworld, camera or world");
      rendering_space_ = v;
      return;
    }
    bracket ? values_skip() : (void)next();
    b_.warn(loc(t), "Option \"" + printable(decl) + "\" is not supported and was ignored");
  }

  void include(const Token& t, const std::string& file) {
    std::filesystem::path p(file);
    if (!p.is_absolute() && !base_dir_.empty()) p = std::filesystem::path(base_dir_) / p;
    std::error_code ec;
    std::string canon = std::filesystem::weakly_canonical(p, ec).string();
    for (const auto& f : files_)
      if (std::filesystem::weakly_canonical(f->filename(), ec).string() == canon)
        fail(t, "Include cycle: \"" + printable(file) + "\" is already being read");
    if (files_.size() >= kMaxIncludeDepth) fail(t, "Include nested deeper than " + std::to_string(kMaxIncludeDepth) + " files");
    if (peeked_) fail(t, "internal: Include with a pending token");
    files_.push_back(Tokenizer::from_file(p.string(), loc(t)));
    b_.including(files_.back()->filename(), files_.back()->size());
  }

  ParserTarget& b_;
  std::string base_dir_;
  WarningSink warn_sink_ = [this](const std::string& s) { b_.warn_line(s); };
  std::vector<std::unique_ptr<Tokenizer>> files_;
  Tokenizer* current_ = nullptr;
  std::optional<Token> peeked_;
  GraphicsState gs_;
  std::vector<GraphicsState> stack_;
  std::vector<SourceLocation> stack_where_;
  std::vector<bool> transform_only_;
  std::map<std::string, std::pair<glm::dmat4, glm::dmat4>> named_cs_;  // at the start and end of the motion
  std::array<glm::dmat4, 2> camera_from_world_{glm::dmat4(1.0), glm::dmat4(1.0)};
  glm::dmat4 render_from_world_{1.0};
  std::array<double, 2> transform_times_{0.0, 1.0};
  std::string rendering_space_ = "cameraworld";
  std::map<std::string, MaterialHandle> named_materials_;
  bool in_world_ = false;
  std::vector<size_t> object_depth_;  // stack_ size just after each open ObjectBegin
};

}  // namespace

void parse_file(const std::string& path, ParserTarget& target) {
  std::string dir = std::filesystem::path(path).parent_path().string();
  Parser p(target, dir);
  p.run(Tokenizer::from_file(path, SourceLocation{path, 0, 0}));
}

void parse_string(const std::string& text, const std::string& name, const std::string& base_dir, ParserTarget& target) {
  Parser p(target, base_dir);
  p.run(std::make_unique<Tokenizer>(text, name));
}

}  // namespace lantern::pbrt
