// What a parser on another thread hands to the real target: the calls it
// would have made, recorded in order and replayed later on the thread that
// owns the target. This is how pbrt-v4's Import is parsed in parallel with
// the file that imports it (docs/scene-format.md, "Import").
#pragma once

#include <atomic>
#include <condition_variable>
#include <deque>
#include <exception>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <variant>
#include <vector>

#include "scene/pbrt/parser_target.h"

namespace lantern::pbrt {

// A material the recorder hands out stands for one the real target makes
// at replay: this kind, and an index into the replay's handles.
inline constexpr uint32_t kDeferredMaterialKind = 0xFF;
inline bool deferred(MaterialHandle h) { return (h.bits >> 24) == kDeferredMaterialKind; }

namespace recorded {
struct Warn { SourceLocation where; std::string what; };
struct WarnLine { std::string line; };
struct Including { std::string path; size_t bytes = 0; };
// Material or MakeNamedMaterial (named: the name it defines); makes the
// material of deferred index `handle`.
struct Material { std::string type; ParamSet ps; uint32_t handle = 0; std::optional<std::string> named; };
// NamedMaterial: deferred index `handle` is whatever the name means when
// the call is replayed (a material of the importing file, or of an earlier
// Import, or one defined further up the same file).
struct NamedMaterial { std::string name; SourceLocation where; uint32_t handle = 0; };
struct Texture { std::string name, value_type, cls; ParamSet ps; Mat4 ctm; };
struct Shape { std::string type; ParamSet ps; std::shared_ptr<const GraphicsState> gs; };
struct Light { std::string type; ParamSet ps; Mat4 ctm; std::string medium; SourceLocation medium_where; };
struct Medium { std::string name; ParamSet ps; Mat4 render_from_medium; };
struct BeginObject { std::string name; SourceLocation where; };
struct EndObject { SourceLocation where; };
struct Instance { std::string name; glm::dmat4 m0, m1; SourceLocation where; };
}  // namespace recorded

using RecordedCall = std::variant<recorded::Warn, recorded::WarnLine, recorded::Including, recorded::Material,
                                  recorded::NamedMaterial, recorded::Texture, recorded::Shape, recorded::Light,
                                  recorded::Medium, recorded::BeginObject, recorded::EndObject, recorded::Instance>;

// The calls of one recording on their way from the parsing thread to the
// replaying one, in batches. The parsing thread waits while the calls
// waiting here hold more than `max_bytes` (a file far larger than memory
// then streams through instead of being held whole).
class CallStream {
 public:
  explicit CallStream(size_t max_bytes) : max_bytes_(max_bytes) {}
  // Parsing thread: hands over a batch; false when the stream was
  // cancelled (stop parsing).
  bool push(std::vector<RecordedCall>&& calls, size_t bytes);
  // Parsing thread: an empty batch to fill, with the room of one replayed
  // (a batch is a megabyte: fresh ones would be mapped and unmapped).
  std::vector<RecordedCall> spare();
  // Parsing thread, last: the error that stopped the parse, if any.
  void finish(std::exception_ptr error);
  // Replaying thread: the next batch; waits for one. False at the end of
  // the stream, with error() then telling how it ended.
  bool pop(std::vector<RecordedCall>& calls);
  // Replaying thread: a replayed batch back, for spare().
  void recycle(std::vector<RecordedCall>&& calls);
  std::exception_ptr error() const { return error_; }
  // Either thread: stop the parse (its calls will not be replayed).
  void cancel();
  bool cancelled() const { return cancelled_.load(std::memory_order_relaxed); }

 private:
  std::mutex mutex_;
  std::condition_variable changed_;
  std::deque<std::pair<std::vector<RecordedCall>, size_t>> batches_;
  std::vector<std::vector<RecordedCall>> spares_;
  size_t held_bytes_ = 0;
  const size_t max_bytes_;
  bool finished_ = false;
  std::atomic<bool> cancelled_{false};  // set under the lock, also read without it
  std::exception_ptr error_;
};

// Thrown in the parsing thread when its stream was cancelled.
struct RecordingCancelled {};

// The target a parser on another thread drives: records each call into the
// stream, in batches. Materials are deferred handles.
class Recorder final : public ParserTarget {
 public:
  // real: answers lenient() (read only).
  Recorder(const ParserTarget& real, CallStream& out) : real_(real), out_(out) {}
  // Hands over what is left; after the parse.
  void flush() const;
  // NamedMaterial in the recorded file: a deferred handle for the name.
  MaterialHandle named_material(const std::string& name, const SourceLocation& where);

  void warn(const SourceLocation& where, const std::string& what) const override;
  void warn_line(const std::string& line) const override;
  bool lenient() const override { return real_.lenient(); }
  void including(const std::string& path, size_t bytes) override;
  void camera(const std::string&, const ParamSet&, const glm::dmat4&, const glm::dmat4&) override { options(); }
  void camera_medium(const std::string&, const SourceLocation&) override { options(); }
  void film(const std::string&, const ParamSet&) override { options(); }
  void sampler(const std::string&, const ParamSet&) override { options(); }
  void integrator(const std::string&, const ParamSet&) override { options(); }
  void pixel_filter(const std::string&, const ParamSet&) override { options(); }
  void begin_world(const glm::dmat4&, double, double) override { options(); }
  MaterialHandle material(const std::string& type, const ParamSet& ps, const std::map<std::string, MaterialHandle>&,
                          const std::string&) override;
  // MakeNamedMaterial: as material(), the name defined at replay.
  MaterialHandle named_definition(const std::string& name, const std::string& type, const ParamSet& ps);
  void texture(const std::string& name, const std::string& value_type, const std::string& cls, const ParamSet& ps,
               const Mat4& ctm, const std::string&) override;
  void shape(const std::string& type, const ParamSet& ps, const GraphicsState& gs, const std::string&) override;
  void light(const std::string& type, const ParamSet& ps, const Mat4& ctm, const std::string&, const std::string& medium,
             const SourceLocation& medium_where) override;
  void medium(const std::string& name, const ParamSet& ps, const Mat4& render_from_medium, const std::string&) override;
  void begin_object(const std::string& name, const SourceLocation& where) override;
  void end_object(const SourceLocation& where) override;
  void object_instance(const std::string& name, const glm::dmat4& m0, const glm::dmat4& m1,
                       const SourceLocation& where) override;

 private:
  [[noreturn]] static void options();
  void add(RecordedCall&& c, size_t bytes) const;
  const FileName& own_name(const FileName& f);
  const ParserTarget& real_;
  CallStream& out_;
  mutable std::vector<RecordedCall> batch_;
  mutable size_t batch_bytes_ = 0;
  uint32_t handles_ = 0;
  std::shared_ptr<const GraphicsState> last_state_;
  FileName own_name_;
};

// Replays recorded calls on the real target, as the parser would have made
// them there: with the real materials in place of deferred ones, and each
// directive's unused parameters reported after its call.
class Replayer {
 public:
  // named: the importing parser's named materials, which NamedMaterial reads
  // and MakeNamedMaterial extends, as an Include would.
  Replayer(ParserTarget& target, WarningSink* sink, std::string base_dir, std::map<std::string, MaterialHandle>& named)
      : target_(target), sink_(sink), base_dir_(std::move(base_dir)), named_(named) {}
  void replay(std::vector<RecordedCall>& calls);

 private:
  MaterialHandle real(MaterialHandle h) const;
  void set_handle(uint32_t index, MaterialHandle h);
  const GraphicsState& real_state(const std::shared_ptr<const GraphicsState>& gs);
  void call(recorded::Material& c);
  void call(recorded::NamedMaterial& c);
  void call(recorded::Shape& c);
  ParamSet& own(ParamSet& ps) const {
    ps.warn = sink_;
    return ps;
  }

  ParserTarget& target_;
  WarningSink* sink_;
  std::string base_dir_;
  std::map<std::string, MaterialHandle>& named_;
  std::vector<MaterialHandle> handles_;
  std::shared_ptr<const GraphicsState> recorded_state_;  // the last shape's, and
  GraphicsState state_;                                  // it with real materials
};

}  // namespace lantern::pbrt
