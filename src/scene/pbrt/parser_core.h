// The pbrt parser itself (parser.cpp: tokens and directives;
// parser_params.cpp: parameter lists; imports.cpp: Include and Import). Internal to scene/pbrt:
// the rest of the program calls parse_file and parse_string (parser.h).
#pragma once

#include <array>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "scene/pbrt/parser_target.h"
#include "scene/pbrt/tokenizer.h"

namespace lantern::pbrt {

class ImportQueue;
class Recorder;

// pbrt's directives, looked up once per directive by name.
enum class Directive {
  Unknown, Translate, Scale, Rotate, LookAt, Transform, ConcatTransform, Identity, CoordinateSystem,
  CoordSysTransform, ActiveTransform, TransformTimes, ReverseOrientation, AttributeBegin, TransformBegin,
  AttributeEnd, TransformEnd, WorldBegin, WorldEnd, Camera, ColorSpace, Film, Sampler, Integrator, PixelFilter,
  Accelerator, Option, Include, Import, Material, MakeNamedMaterial, NamedMaterial, Texture, LightSource,
  AreaLightSource, Shape, MediumInterface, MakeNamedMedium, Attribute, ObjectBegin, ObjectEnd, ObjectInstance
};

class Parser {
 public:
  Parser(ParserTarget& b, std::string base_dir) : b_(&b), base_dir_(std::move(base_dir)) {}
  // A parser for an Import'ed file: the importer's state at the Import and
  // its target; names_at_replay: the file is recorded (its material names
  // are resolved at replay, so the importer's are not copied).
  Parser(const Parser& importer, bool names_at_replay);
  Parser(const Parser&) = delete;
  Parser& operator=(const Parser&) = delete;
  ~Parser();

  // Parses `root` (and what it includes) to its end.
  void run(std::unique_ptr<Tokenizer> root);
  // Import'ed files parse on up to `threads` threads (1: in place).
  void set_import_threads(unsigned threads) { import_threads_ = threads; }

 private:
  // --- tokens (parser.cpp) ---
  Token next();
  Token peek();
  // (the token's own file: the parser may have read on into the next)
  SourceLocation loc(const Token& t) const { return (t.source ? t.source : current_)->location(t); }
  [[noreturn]] void fail(const Token& t, const std::string& what) const { throw InputError(loc(t), what); }
  static std::string describe(const Token& t);
  std::string expect_string(const char* what);
  double to_number(const Token& t);
  template <size_t N>
  std::array<double, N> numbers(const char* what);

  // --- parameter lists (parser_params.cpp) ---
  ParamSet params(const Token& at, const std::string& directive, const char* kind, const char* attributes = nullptr);
  ParamSet own_params(const Token& at, const std::string& directive);
  void value(Param& p, const Token& v);
  void values(Param& p, const Token& decl);
  void values_skip();
  // After the target's call: its unused parameters reported (at replay,
  // for a recorded file).
  void done_with(const ParamSet& ps) const;

  // --- directives (parser.cpp) ---
  void directive(const Token& t);
  void transform(Directive d, const Token& t);
  void attribute_end(Directive d, const Token& t);
  void world_begin();
  void camera(const Token& t);
  void options(Directive d, const Token& t);
  void material(Directive d, const Token& t);
  void shape(const Token& t);
  void attribute(const Token& t);
  void object_begin(const Token& t);
  void object_end(const Token& t);
  void object_instance(const Token& t);
  glm::dmat4 look_at(const Token& t, glm::dvec3 pos, glm::dvec3 look, glm::dvec3 up);
  glm::dmat4 render_from_world() const;
  // (where: the directive's, taken before its parameters were read: reading
  // them may have reached the next file)
  void still(const char* what, const SourceLocation& where) const;
  Mat4 render(const glm::dmat4& world_from_object) const { return Mat4(render_from_world_ * world_from_object); }
  void option(const Token& t, const std::string& decl);
  void push_state(const Token& t, bool transform_only);

  // --- Include and Import (imports.cpp) ---
  std::string resolve(const Token& t, const std::string& file) const;
  // The file read, and reported to the target (progress).
  std::unique_ptr<Tokenizer> open(const std::string& path, const SourceLocation& from);
  void include(const Token& t, const std::string& file);
  void import(const Token& t, const std::string& file);
  // Before anything reads what earlier Imports define: their calls replayed.
  void settle();
  void check_balanced(const Token& end) const;

  ParserTarget* b_;
  std::string base_dir_;
  WarningSink warn_sink_ = [this](const std::string& s) { b_->warn_line(s); };
  std::vector<std::unique_ptr<Tokenizer>> files_;
  std::vector<std::unique_ptr<Tokenizer>> finished_;  // ended during the current directive
  Tokenizer* current_ = nullptr;
  std::optional<Token> peeked_;
  GraphicsState gs_;
  std::vector<GraphicsState> stack_;
  std::vector<SourceLocation> stack_where_;
  std::vector<bool> transform_only_;
  std::map<std::string, std::pair<glm::dmat4, glm::dmat4>> named_cs_;  // at the start and end of the motion
  std::array<glm::dmat4, 2> camera_from_world_{glm::dmat4(1.0), glm::dmat4(1.0)};
  glm::dmat4 render_from_world_{1.0}, world_from_render_{1.0};
  std::array<double, 2> transform_times_{0.0, 1.0};
  std::string rendering_space_ = "cameraworld";
  std::map<std::string, MaterialHandle> named_materials_;
  bool in_world_ = false;
  std::vector<size_t> object_depth_;  // stack_ size just after each open ObjectBegin

  // Import: the files being read by the parsers that imported this one
  // (canonical names, for cycles); the attribute depth this parser's file
  // started at (it may not close more); the recorder this parser drives
  // when it parses on another thread; the parallel Imports in flight.
  std::vector<std::string> ancestors_;
  size_t floor_ = 0;
  Recorder* recorder_ = nullptr;
  unsigned import_threads_ = 1;
  std::unique_ptr<ImportQueue> imports_;
};

}  // namespace lantern::pbrt
