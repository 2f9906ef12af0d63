#include "scene/pbrt/parser.h"

#include <algorithm>
#include <charconv>
#include <filesystem>
#include <glm/gtc/matrix_transform.hpp>
#include <tuple>
#include <unordered_map>

#include "math/motion.h"
#include "scene/pbrt/imports.h"
#include "scene/pbrt/parser_core.h"
#include "scene/pbrt/recorder.h"

namespace lantern::pbrt {

namespace {

constexpr size_t kMaxAttributeDepth = 10000;

Directive directive_named(std::string_view d) {
  static const std::unordered_map<std::string_view, Directive> kNames = {
      {"Translate", Directive::Translate}, {"Scale", Directive::Scale}, {"Rotate", Directive::Rotate},
      {"LookAt", Directive::LookAt}, {"Transform", Directive::Transform},
      {"ConcatTransform", Directive::ConcatTransform}, {"Identity", Directive::Identity},
      {"CoordinateSystem", Directive::CoordinateSystem}, {"CoordSysTransform", Directive::CoordSysTransform},
      {"ActiveTransform", Directive::ActiveTransform}, {"TransformTimes", Directive::TransformTimes},
      {"ReverseOrientation", Directive::ReverseOrientation}, {"AttributeBegin", Directive::AttributeBegin},
      {"TransformBegin", Directive::TransformBegin}, {"AttributeEnd", Directive::AttributeEnd},
      {"TransformEnd", Directive::TransformEnd}, {"WorldBegin", Directive::WorldBegin},
      {"WorldEnd", Directive::WorldEnd}, {"Camera", Directive::Camera}, {"ColorSpace", Directive::ColorSpace},
      {"Film", Directive::Film}, {"Sampler", Directive::Sampler}, {"Integrator", Directive::Integrator},
      {"PixelFilter", Directive::PixelFilter}, {"Accelerator", Directive::Accelerator},
      {"Option", Directive::Option}, {"Include", Directive::Include}, {"Import", Directive::Import},
      {"Material", Directive::Material}, {"MakeNamedMaterial", Directive::MakeNamedMaterial},
      {"NamedMaterial", Directive::NamedMaterial}, {"Texture", Directive::Texture},
      {"LightSource", Directive::LightSource}, {"AreaLightSource", Directive::AreaLightSource},
      {"Shape", Directive::Shape}, {"MediumInterface", Directive::MediumInterface},
      {"MakeNamedMedium", Directive::MakeNamedMedium}, {"Attribute", Directive::Attribute},
      {"ObjectBegin", Directive::ObjectBegin}, {"ObjectEnd", Directive::ObjectEnd},
      {"ObjectInstance", Directive::ObjectInstance}};
  auto it = kNames.find(d);
  return it == kNames.end() ? Directive::Unknown : it->second;
}

}  // namespace

Parser::~Parser() = default;

void Parser::run(std::unique_ptr<Tokenizer> root) {
  files_.push_back(std::move(root));
  try {
    for (;;) {
      Token t = next();
      if (t.kind == TokenKind::End) break;
      if (t.kind != TokenKind::Identifier) fail(t, std::string("expected a directive name, found ") + token_kind_name(t.kind) + describe(t));
      directive(t);
      finished_.clear();
    }
    if (stack_.size() > floor_) throw InputError(stack_where_.back(), "AttributeBegin without a matching AttributeEnd");
  } catch (...) {
    // An Import before the error comes first in the file: its calls, and
    // its own error if it has one, before this one.
    settle();
    throw;
  }
  settle();
}

// --- tokens --------------------------------------------------------------

Token Parser::next() {
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
    // Kept to the end of the directive, whose tokens may still point into it.
    finished_.push_back(std::move(files_.back()));
    files_.pop_back();
  }
  return Token{};
}

Token Parser::peek() {
  if (!peeked_) peeked_ = next();
  return *peeked_;
}

std::string Parser::describe(const Token& t) {
  if (t.kind == TokenKind::End) return "";
  return " \"" + printable(t.text) + "\"";
}

std::string Parser::expect_string(const char* what) {
  Token t = next();
  if (t.kind != TokenKind::String)
    fail(t, std::string("expected ") + what + " (a quoted string), found " + token_kind_name(t.kind) + describe(t));
  return unescape(t.text);
}

double Parser::to_number(const Token& t) {
  double v = 0.0;
  const char* b = t.text.data();
  const char* e = b + t.text.size();
  if (*b == '+') ++b;
  auto [ptr, ec] = std::from_chars(b, e, v);
  if (ec != std::errc() || ptr != e) fail(t, "malformed number" + describe(t));
  return v;
}

template <size_t N>
std::array<double, N> Parser::numbers(const char* what) {
  std::array<double, N> v{};
  const bool bracket = peek().kind == TokenKind::OpenBracket;
  if (bracket) next();
  for (size_t i = 0; i < N; ++i) {
    Token x = next();
    if (x.kind != TokenKind::Number)
      fail(x, std::string(what) + " expects " + std::to_string(N) + " numbers; found " + token_kind_name(x.kind) + describe(x));
    v[i] = to_number(x);
  }
  if (bracket) {
    Token c = next();
    if (c.kind != TokenKind::CloseBracket) fail(c, std::string(what) + ": expected ']' after " + std::to_string(N) + " numbers");
  }
  return v;
}

void Parser::done_with(const ParamSet& ps) const {
  // A recorded call has not been made yet: the replay reports.
  if (!recorder_) ps.warn_unused();
}

// --- directives ------------------------------------------------------------

void Parser::directive(const Token& t) {
  const Directive d = directive_named(t.text);
  auto world_only = [&] {
    if (!in_world_) fail(t, std::string(t.text) + " is only allowed after WorldBegin");
  };
  switch (d) {
    case Directive::Translate: case Directive::Scale: case Directive::Rotate: case Directive::LookAt:
    case Directive::Transform: case Directive::ConcatTransform: case Directive::Identity:
    case Directive::CoordinateSystem: case Directive::CoordSysTransform: case Directive::ActiveTransform:
      return transform(d, t);
    case Directive::ReverseOrientation:
      gs_.reverse_orientation = !gs_.reverse_orientation;
      return;
    case Directive::AttributeBegin: case Directive::TransformBegin:
      return push_state(t, d == Directive::TransformBegin);
    case Directive::AttributeEnd: case Directive::TransformEnd:
      return attribute_end(d, t);
    case Directive::WorldBegin:
      if (in_world_) fail(t, "WorldBegin is only allowed before WorldBegin");
      return world_begin();
    case Directive::WorldEnd:
      return world_only();
    case Directive::Camera:
      return camera(t);
    case Directive::ColorSpace: {
      // Graphics state, as in pbrt-v4: allowed anywhere, scoped by
      // AttributeBegin/End.
      const std::string name = expect_string("a colour space name");
      gs_.color_space = ColorSpace::named(name);
      if (!gs_.color_space)
        fail(t, "ColorSpace \"" + printable(name) + "\" is unknown; expected srgb, rec2020, dci-p3 or aces2065-1");
      return;
    }
    case Directive::TransformTimes: case Directive::Film: case Directive::Sampler: case Directive::Integrator:
    case Directive::PixelFilter: case Directive::Accelerator: case Directive::Option:
      return options(d, t);
    case Directive::Include:
      return include(t, expect_string("a file name"));
    case Directive::Import:
      return import(t, expect_string("a file name"));
    case Directive::Material: case Directive::MakeNamedMaterial: case Directive::NamedMaterial:
      world_only();
      return material(d, t);
    case Directive::Texture: {
      world_only();
      std::string name = expect_string("a texture name");
      std::string vtype = expect_string("a texture value type");
      std::string cls = expect_string("a texture class");
      ParamSet ps = params(t, "Texture \"" + printable(name) + "\"", "texture", "texture");
      still("texture", ps.where);
      b_->texture(name, vtype, cls, ps, render(gs_.world_from_object), base_dir_);
      return done_with(ps);
    }
    case Directive::LightSource: {
      world_only();
      std::string type = expect_string("a light type");
      ParamSet ps = params(t, "LightSource \"" + printable(type) + "\"", "light", "light");
      still("light", ps.where);
      b_->light(type, ps, render(gs_.world_from_object), base_dir_, gs_.outside_medium, gs_.medium_where);
      return done_with(ps);
    }
    case Directive::AreaLightSource: {
      world_only();
      std::string type = expect_string("an area light type");
      ParamSet ps = params(t, "AreaLightSource \"" + printable(type) + "\"", "arealight", "light");
      // pbrt-v3 calls the diffuse area light "area".
      if (type != "diffuse" && type != "area")
        ps.fail("area light type \"" + printable(type) + "\" is not supported; expected \"diffuse\" (pbrt-v3: \"area\")");
      gs_.area_light = std::move(ps);
      gs_.area_light_dir = base_dir_;
      return;
    }
    case Directive::Shape:
      world_only();
      return shape(t);
    case Directive::MediumInterface:
      // One name sets both sides, as in pbrt.
      gs_.inside_medium = expect_string("a medium name");
      gs_.outside_medium = peek().kind == TokenKind::String ? expect_string("a medium name") : gs_.inside_medium;
      gs_.medium_where = loc(t);
      return;
    case Directive::MakeNamedMedium: {
      std::string name = expect_string("a medium name");
      ParamSet ps = params(t, "MakeNamedMedium \"" + printable(name) + "\"", "medium", "medium");
      still("medium", ps.where);
      b_->medium(name, ps, render(gs_.world_from_object), base_dir_);
      return done_with(ps);
    }
    case Directive::Attribute:
      return attribute(t);
    case Directive::ObjectBegin:
      world_only();
      return object_begin(t);
    case Directive::ObjectEnd:
      world_only();
      return object_end(t);
    case Directive::ObjectInstance:
      world_only();
      return object_instance(t);
    case Directive::Unknown:
      break;
  }
  fail(t, "unknown directive \"" + printable(t.text) + "\"");
}

// pbrt's two current transformations, at the start and the end of the
// motion; ActiveTransform chooses which the directives change.
void Parser::transform(Directive d, const Token& t) {
  auto apply = [&](auto&& f) {
    if (gs_.active_transforms & 1) gs_.world_from_object = f(gs_.world_from_object);
    if (gs_.active_transforms & 2) gs_.world_from_object_end = f(gs_.world_from_object_end);
  };
  switch (d) {
    case Directive::Translate: {
      const auto v = numbers<3>("Translate");
      return apply([&](const glm::dmat4& m) { return glm::translate(m, glm::dvec3(v[0], v[1], v[2])); });
    }
    case Directive::Scale: {
      const auto v = numbers<3>("Scale");
      return apply([&](const glm::dmat4& m) { return glm::scale(m, glm::dvec3(v[0], v[1], v[2])); });
    }
    case Directive::Rotate: {
      const auto v = numbers<4>("Rotate");
      const glm::dvec3 axis{v[1], v[2], v[3]};
      if (glm::length(axis) == 0.0) fail(t, "Rotate: the axis must not be zero");
      return apply([&](const glm::dmat4& m) { return glm::rotate(m, glm::radians(v[0]), glm::normalize(axis)); });
    }
    case Directive::LookAt: {
      const auto v = numbers<9>("LookAt");
      const glm::dmat4 l = look_at(t, glm::dvec3(v[0], v[1], v[2]), glm::dvec3(v[3], v[4], v[5]), glm::dvec3(v[6], v[7], v[8]));
      return apply([&](const glm::dmat4& m) { return m * l; });
    }
    case Directive::Transform: case Directive::ConcatTransform: {
      const auto v = numbers<16>(d == Directive::Transform ? "Transform" : "ConcatTransform");
      glm::dmat4 n;
      for (int i = 0; i < 16; ++i) n[i / 4][i % 4] = v[size_t(i)];
      return apply([&](const glm::dmat4& m) { return d == Directive::Transform ? n : m * n; });
    }
    case Directive::Identity:
      return apply([](const glm::dmat4&) { return glm::dmat4(1.0); });
    case Directive::CoordinateSystem:
      named_cs_[expect_string("a coordinate system name")] = {gs_.world_from_object, gs_.world_from_object_end};
      return;
    case Directive::CoordSysTransform: {
      std::string n = expect_string("a coordinate system name");
      auto it = named_cs_.find(n);
      if (it == named_cs_.end()) b_->warn(loc(t), "unknown coordinate system \"" + printable(n) + "\" ignored");
      else std::tie(gs_.world_from_object, gs_.world_from_object_end) = it->second;
      return;
    }
    default: {  // ActiveTransform
      const Token which = next();
      if (which.kind != TokenKind::Identifier || (which.text != "StartTime" && which.text != "EndTime" && which.text != "All"))
        fail(which, "ActiveTransform expects StartTime, EndTime or All" + describe(which));
      gs_.active_transforms = which.text == "StartTime" ? 1 : which.text == "EndTime" ? 2 : 3;
    }
  }
}

void Parser::push_state(const Token& t, bool transform_only) {
  if (stack_.size() >= kMaxAttributeDepth) fail(t, "AttributeBegin nested deeper than " + std::to_string(kMaxAttributeDepth));
  stack_.push_back(gs_);
  stack_where_.push_back(loc(t));
  transform_only_.push_back(transform_only);
}

void Parser::attribute_end(Directive d, const Token& t) {
  const bool attributes = d == Directive::AttributeEnd;
  if (stack_.size() <= floor_)
    fail(t, std::string(t.text) + " without a matching " + (attributes ? "AttributeBegin" : "TransformBegin") +
                (floor_ ? " in the Import'ed file" : ""));
  if (!object_depth_.empty() && object_depth_.back() == stack_.size())
    fail(t, std::string(t.text) + " would close an ObjectBegin; close it with ObjectEnd");
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
}

void Parser::world_begin() {
  in_world_ = true;
  gs_.world_from_object = gs_.world_from_object_end = glm::dmat4(1.0);
  gs_.active_transforms = 3;
  named_cs_["world"] = {gs_.world_from_object, gs_.world_from_object};
  render_from_world_ = render_from_world();
  world_from_render_ = glm::inverse(render_from_world_);
  b_->begin_world(render_from_world_, transform_times_[0], transform_times_[1]);
}

void Parser::camera(const Token& t) {
  if (in_world_) fail(t, "Camera is only allowed before WorldBegin");
  std::string type = expect_string("a camera type");
  ParamSet ps = params(t, "Camera \"" + printable(type) + "\"", "camera");
  const glm::dmat4& ctm = gs_.world_from_object;
  b_->camera(type, ps, ctm, gs_.world_from_object_end);
  b_->camera_medium(gs_.outside_medium, gs_.medium_where);
  camera_from_world_ = {ctm, gs_.world_from_object_end};
  named_cs_["camera"] = {glm::inverse(ctm), glm::inverse(gs_.world_from_object_end)};
  done_with(ps);
}

void Parser::options(Directive d, const Token& t) {
  if (in_world_) fail(t, std::string(t.text) + " is only allowed before WorldBegin");
  if (d == Directive::TransformTimes) {
    const auto v = numbers<2>("TransformTimes");
    if (!(v[1] >= v[0])) fail(t, "TransformTimes: the end time must not come before the start time");
    if (camera_from_world_[0] != camera_from_world_[1] && (v[0] != transform_times_[0] || v[1] != transform_times_[1]))
      fail(t, "TransformTimes after a moving Camera: give the times before the Camera");
    transform_times_ = {v[0], v[1]};
    return;
  }
  std::string type = expect_string("a type name");
  if (d == Directive::Option) return option(t, type);
  const char* kind = d == Directive::Film ? "film" : d == Directive::Sampler ? "sampler"
                   : d == Directive::Integrator ? "integrator" : d == Directive::PixelFilter ? "filter" : "accelerator";
  ParamSet ps = params(t, std::string(t.text) + " \"" + printable(type) + "\"", kind);
  if (d == Directive::Film) b_->film(type, ps);
  else if (d == Directive::Sampler) b_->sampler(type, ps);
  else if (d == Directive::Integrator) b_->integrator(type, ps);
  else if (d == Directive::PixelFilter) b_->pixel_filter(type, ps);
  if (d != Directive::Accelerator) done_with(ps);
}

// Material, MakeNamedMaterial and NamedMaterial. In a file recorded on
// another thread the names mean what they mean at replay, where earlier
// Imports have defined theirs: the recorder defers them.
void Parser::material(Directive d, const Token& t) {
  if (d == Directive::NamedMaterial) {
    std::string name = expect_string("a material name");
    if (recorder_) {
      gs_.material = recorder_->named_material(name, loc(t));
      return;
    }
    settle();
    auto it = named_materials_.find(name);
    if (it == named_materials_.end()) fail(t, "NamedMaterial \"" + printable(name) + "\" was never defined with MakeNamedMaterial");
    gs_.material = it->second;
    return;
  }
  if (d == Directive::Material) {
    std::string type = expect_string("a material type");
    ParamSet ps = params(t, "Material \"" + printable(type) + "\"", "material", "material");
    gs_.material = b_->material(type, ps, named_materials_, base_dir_);
    return done_with(ps);
  }
  std::string name = expect_string("a material name");
  ParamSet ps = params(t, "MakeNamedMaterial \"" + printable(name) + "\"", "material", "material");
  std::string type = ps.get_string("type", "");
  if (type.empty()) ps.fail("needs a \"string type\" parameter");
  if (recorder_) {
    recorder_->named_definition(name, type, ps);
    return;
  }
  settle();
  if (named_materials_.count(name)) b_->warn(ps.where, "material \"" + printable(name) + "\" redefined");
  named_materials_[name] = b_->material(type, ps, named_materials_, base_dir_);
  done_with(ps);
}

void Parser::shape(const Token& t) {
  std::string type = expect_string("a shape type");
  ParamSet ps = params(t, "Shape \"" + printable(type) + "\"", "shape", "shape");
  gs_.render_from_object = render_from_world_ * gs_.world_from_object;
  gs_.render_from_object_end = render_from_world_ * gs_.world_from_object_end;
  b_->shape(type, ps, gs_, base_dir_);
  done_with(ps);
}

// Defaults for the kind's later directives, in the graphics state: a later
// Attribute's value of the same name replaces an earlier one.
void Parser::attribute(const Token& t) {
  const std::string kind = expect_string("an attribute target: shape, light, material, medium or texture");
  if (kind != "shape" && kind != "light" && kind != "material" && kind != "medium" && kind != "texture")
    fail(t, "Attribute \"" + printable(kind) + "\" is unknown; expected shape, light, material, medium or texture");
  std::vector<Param>& defaults = gs_.attributes[kind];
  for (Param& p : own_params(t, "Attribute \"" + kind + "\"").params) {
    auto same = std::find_if(defaults.begin(), defaults.end(), [&](const Param& q) { return q.name == p.name; });
    if (same != defaults.end()) *same = std::move(p);
    else defaults.push_back(std::move(p));
  }
}

// As in pbrt: an object's shapes keep the transform current at their
// definition, and ObjectBegin/End also push and pop the attributes.
void Parser::object_begin(const Token& t) {
  std::string name = expect_string("an object name");
  if (stack_.size() >= kMaxAttributeDepth) fail(t, "AttributeBegin nested deeper than " + std::to_string(kMaxAttributeDepth));
  b_->begin_object(name, loc(t));
  push_state(t, false);
  object_depth_.push_back(stack_.size());
}

void Parser::object_end(const Token& t) {
  if (object_depth_.empty() || object_depth_.back() <= floor_)
    fail(t, std::string("ObjectEnd without ObjectBegin") + (floor_ ? " in the Import'ed file" : ""));
  if (object_depth_.back() != stack_.size())
    fail(t, "ObjectEnd does not close the innermost ObjectBegin (an AttributeBegin inside it is still open?)");
  b_->end_object(loc(t));
  gs_ = stack_.back();
  stack_.pop_back();
  stack_where_.pop_back();
  transform_only_.pop_back();
  object_depth_.pop_back();
}

void Parser::object_instance(const Token& t) {
  std::string name = expect_string("an object name");
  // Objects are stored in render space as defined; an instance places
  // its render-space copy: render_from_world M world_from_render.
  b_->object_instance(name, render_from_world_ * gs_.world_from_object * world_from_render_,
                      render_from_world_ * gs_.world_from_object_end * world_from_render_, loc(t));
}

// pbrt's LookAt: the camera-from-world matrix of a left-handed camera.
glm::dmat4 Parser::look_at(const Token& t, glm::dvec3 pos, glm::dvec3 look, glm::dvec3 up) {
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
glm::dmat4 Parser::render_from_world() const {
  if (rendering_space_ == "world") return glm::dmat4(1.0);
  glm::dmat4 world_from_camera = glm::inverse(camera_from_world_[0]);
  if (camera_from_world_[0] != camera_from_world_[1])
    world_from_camera = interpolate_transform(world_from_camera, glm::inverse(camera_from_world_[1]), 0.5);
  if (rendering_space_ == "camera") return glm::inverse(world_from_camera);
  return glm::translate(glm::dmat4(1.0), -glm::dvec3(world_from_camera[3]));
}
// pbrt-v4 gives lights, textures and media the transform at the start
// of the motion, with a warning when it moves.
void Parser::still(const char* what, const SourceLocation& where) const {
  if (gs_.world_from_object != gs_.world_from_object_end)
    b_->warn(where, std::string("a moving ") + what + " is not supported (nor in pbrt-v4); it stays where the motion starts");
}

// Option "type name" value: renderingcoordinatesystem is read; the
// others warn.
void Parser::option(const Token& t, const std::string& decl) {
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
  b_->warn(loc(t), "Option \"" + printable(decl) + "\" is not supported and was ignored");
}


void parse_file(const std::string& path, ParserTarget& target, unsigned threads) {
  std::string dir = std::filesystem::path(path).parent_path().string();
  Parser p(target, dir);
  p.set_import_threads(threads);
  p.run(Tokenizer::from_file(path, SourceLocation{path, 0, 0}));
}

void parse_string(const std::string& text, const std::string& name, const std::string& base_dir, ParserTarget& target,
                  unsigned threads) {
  Parser p(target, base_dir);
  p.set_import_threads(threads);
  p.run(std::make_unique<Tokenizer>(text, name));
}

}  // namespace lantern::pbrt
