#include "scene/pbrt/recorder.h"

#include <cstring>

namespace lantern::pbrt {

namespace {

// A batch is handed over at about this size, so that replay starts while
// the file is still being parsed. Its calls are one allocation, made
// whole: large enough to be mapped on its own, in huge pages where the
// heap uses them (docs/performance.md, "Huge pages").
constexpr size_t kBatchBytes = size_t(8) << 20;
constexpr size_t kBatchCalls = kBatchBytes / sizeof(RecordedCall) / 2;

size_t bytes_of(const ParamSet& ps) {
  size_t b = ps.params.size() * sizeof(Param);
  for (const Param& p : ps.params) b += p.numbers.size() * sizeof(double) + p.strings.size() * sizeof(std::string);
  return b;
}

bool same_matrix(const glm::dmat4& a, const glm::dmat4& b) { return std::memcmp(&a, &b, sizeof a) == 0; }

// Whether a shape recorded after `b` can share `a`'s state: only the cheap,
// common case is recognised (no area light, no attribute defaults).
bool same_state(const GraphicsState& a, const GraphicsState& b) {
  return !a.area_light && !b.area_light && a.attributes.empty() && b.attributes.empty() &&
         same_matrix(a.render_from_object, b.render_from_object) &&
         same_matrix(a.render_from_object_end, b.render_from_object_end) &&
         same_matrix(a.world_from_object, b.world_from_object) &&
         same_matrix(a.world_from_object_end, b.world_from_object_end) && a.active_transforms == b.active_transforms &&
         a.reverse_orientation == b.reverse_orientation && a.material.has_value() == b.material.has_value() &&
         (!a.material || a.material->bits == b.material->bits) && a.inside_medium == b.inside_medium &&
         a.outside_medium == b.outside_medium && a.medium_where.file == b.medium_where.file &&
         a.medium_where.line == b.medium_where.line && a.medium_where.column == b.medium_where.column &&
         a.color_space == b.color_space;
}

}  // namespace

// --- CallStream --------------------------------------------------------------

bool CallStream::push(std::vector<RecordedCall>&& calls, size_t bytes) {
  std::unique_lock<std::mutex> lock(mutex_);
  changed_.wait(lock, [&] { return cancelled_ || held_bytes_ == 0 || held_bytes_ + bytes <= max_bytes_; });
  if (cancelled_) return false;
  held_bytes_ += bytes;
  batches_.emplace_back(std::move(calls), bytes);
  changed_.notify_all();
  return true;
}

std::vector<RecordedCall> CallStream::spare() {
  std::lock_guard<std::mutex> lock(mutex_);
  std::vector<RecordedCall> v;
  if (!spares_.empty()) {
    v = std::move(spares_.back());
    spares_.pop_back();
  }
  return v;
}

void CallStream::recycle(std::vector<RecordedCall>&& calls) {
  calls.clear();
  std::lock_guard<std::mutex> lock(mutex_);
  if (spares_.size() < 2 && !cancelled_) spares_.push_back(std::move(calls));
}

void CallStream::finish(std::exception_ptr error) {
  std::lock_guard<std::mutex> lock(mutex_);
  finished_ = true;
  error_ = std::move(error);
  changed_.notify_all();
}

bool CallStream::pop(std::vector<RecordedCall>& calls) {
  std::unique_lock<std::mutex> lock(mutex_);
  changed_.wait(lock, [&] { return !batches_.empty() || finished_; });
  if (batches_.empty()) return false;
  calls = std::move(batches_.front().first);
  held_bytes_ -= batches_.front().second;
  batches_.pop_front();
  changed_.notify_all();
  return true;
}

void CallStream::cancel() {
  std::lock_guard<std::mutex> lock(mutex_);
  cancelled_ = true;
  batches_.clear();
  held_bytes_ = 0;
  changed_.notify_all();
}

// --- Recorder ----------------------------------------------------------------

void Recorder::options() {
  // The parser allows these before WorldBegin only, and Import is
  // recorded in the world only.
  throw std::logic_error("a rendering option inside an Import'ed file");
}

void Recorder::add(RecordedCall&& c, size_t bytes) const {
  // (a cancelled file stops at its next call, not at its end)
  if (out_.cancelled()) throw RecordingCancelled{};
  if (batch_.capacity() == 0) batch_.reserve(kBatchCalls);
  batch_.push_back(std::move(c));
  batch_bytes_ += sizeof(RecordedCall) + bytes;
  if (batch_bytes_ >= kBatchBytes || batch_.size() == kBatchCalls) flush();
}

void Recorder::flush() const {
  if (batch_.empty()) return;
  const size_t bytes = batch_bytes_;
  std::vector<RecordedCall> calls = out_.spare();
  calls.swap(batch_);
  batch_bytes_ = 0;
  if (!out_.push(std::move(calls), bytes)) throw RecordingCancelled{};
}

void Recorder::warn(const SourceLocation& where, const std::string& what) const {
  add(recorded::Warn{where, what}, what.size());
}
void Recorder::warn_line(const std::string& line) const { add(recorded::WarnLine{line}, line.size()); }
void Recorder::including(const std::string& path, size_t bytes) { add(recorded::Including{path, bytes}, path.size()); }

MaterialHandle Recorder::material(const std::string& type, const ParamSet& ps,
                                  const std::map<std::string, MaterialHandle>&, const std::string&) {
  const uint32_t h = handles_++;
  add(recorded::Material{type, ps, h, std::nullopt}, bytes_of(ps));
  return MaterialHandle{kDeferredMaterialKind << 24 | h};
}

MaterialHandle Recorder::named_definition(const std::string& name, const std::string& type, const ParamSet& ps) {
  const uint32_t h = handles_++;
  add(recorded::Material{type, ps, h, name}, bytes_of(ps));
  return MaterialHandle{kDeferredMaterialKind << 24 | h};
}

MaterialHandle Recorder::named_material(const std::string& name, const SourceLocation& where) {
  const uint32_t h = handles_++;
  add(recorded::NamedMaterial{name, where, h}, name.size());
  return MaterialHandle{kDeferredMaterialKind << 24 | h};
}

void Recorder::texture(const std::string& name, const std::string& value_type, const std::string& cls,
                       const ParamSet& ps, const Mat4& ctm, const std::string&) {
  add(recorded::Texture{name, value_type, cls, ps, ctm}, bytes_of(ps));
}

void Recorder::shape(const std::string& type, const ParamSet& ps, const GraphicsState& gs, const std::string&) {
  size_t bytes = bytes_of(ps);
  if (!last_state_ || !same_state(*last_state_, gs)) {
    last_state_ = std::make_shared<const GraphicsState>(gs);
    bytes += sizeof(GraphicsState);
  }
  add(recorded::Shape{type, ps, last_state_}, bytes);
}

void Recorder::light(const std::string& type, const ParamSet& ps, const Mat4& ctm, const std::string&,
                     const std::string& medium, const SourceLocation& medium_where) {
  add(recorded::Light{type, ps, ctm, medium, medium_where}, bytes_of(ps));
}

void Recorder::medium(const std::string& name, const ParamSet& ps, const Mat4& render_from_medium, const std::string&) {
  add(recorded::Medium{name, ps, render_from_medium}, bytes_of(ps));
}

void Recorder::begin_object(const std::string& name, const SourceLocation& where) {
  add(recorded::BeginObject{name, where}, 0);
}
void Recorder::end_object(const SourceLocation& where) { add(recorded::EndObject{where}, 0); }

void Recorder::object_instance(const std::string& name, const glm::dmat4& m0, const glm::dmat4& m1,
                               const SourceLocation& where) {
  add(recorded::Instance{name, m0, m1, {own_name(where.file), where.line, where.column}}, 0);
}

// A copy of the name of its own, for the locations of the recording: the
// parsing thread's copies and the replaying thread's then count their
// references apart (one count shared by two cores costs more than the
// rest of a placement's recording).
const FileName& Recorder::own_name(const FileName& f) {
  if (f.str() != own_name_.str()) own_name_ = FileName(std::string(f.str()));
  return own_name_;
}

// --- Replayer ----------------------------------------------------------------

MaterialHandle Replayer::real(MaterialHandle h) const { return deferred(h) ? handles_.at(h.index()) : h; }

void Replayer::set_handle(uint32_t index, MaterialHandle h) {
  if (handles_.size() <= index) handles_.resize(size_t(index) + 1);
  handles_[index] = h;
}

const GraphicsState& Replayer::real_state(const std::shared_ptr<const GraphicsState>& gs) {
  // Shapes of one state share it: translated once.
  if (gs != recorded_state_) {
    recorded_state_ = gs;
    state_ = *gs;
    if (state_.material) state_.material = real(*state_.material);
    if (state_.area_light) own(*state_.area_light);
  }
  return state_;
}

void Replayer::call(recorded::Material& c) {
  // As the parser does it on its own thread (parser.cpp, MakeNamedMaterial).
  if (c.named && named_.count(*c.named)) target_.warn(c.ps.where, "material \"" + printable(*c.named) + "\" redefined");
  const MaterialHandle h = target_.material(c.type, own(c.ps), named_, base_dir_);
  set_handle(c.handle, h);
  if (c.named) named_[*c.named] = h;
  c.ps.warn_unused();
}

void Replayer::call(recorded::NamedMaterial& c) {
  auto it = named_.find(c.name);
  if (it == named_.end())
    throw InputError(c.where, "NamedMaterial \"" + printable(c.name) + "\" was never defined with MakeNamedMaterial");
  set_handle(c.handle, it->second);
}

void Replayer::call(recorded::Shape& c) {
  target_.shape(c.type, own(c.ps), real_state(c.gs), base_dir_);
  c.ps.warn_unused();
}

void Replayer::replay(std::vector<RecordedCall>& calls) {
  for (RecordedCall& rc : calls) {
    std::visit(
        [&](auto& c) {
          using T = std::decay_t<decltype(c)>;
          if constexpr (std::is_same_v<T, recorded::Warn>) {
            target_.warn(c.where, c.what);
          } else if constexpr (std::is_same_v<T, recorded::WarnLine>) {
            target_.warn_line(c.line);
          } else if constexpr (std::is_same_v<T, recorded::Including>) {
            target_.including(c.path, c.bytes);
          } else if constexpr (std::is_same_v<T, recorded::Texture>) {
            target_.texture(c.name, c.value_type, c.cls, own(c.ps), c.ctm, base_dir_);
            c.ps.warn_unused();
          } else if constexpr (std::is_same_v<T, recorded::Light>) {
            target_.light(c.type, own(c.ps), c.ctm, base_dir_, c.medium, c.medium_where);
            c.ps.warn_unused();
          } else if constexpr (std::is_same_v<T, recorded::Medium>) {
            target_.medium(c.name, own(c.ps), c.render_from_medium, base_dir_);
            c.ps.warn_unused();
          } else if constexpr (std::is_same_v<T, recorded::BeginObject>) {
            target_.begin_object(c.name, c.where);
          } else if constexpr (std::is_same_v<T, recorded::EndObject>) {
            target_.end_object(c.where);
          } else if constexpr (std::is_same_v<T, recorded::Instance>) {
            target_.object_instance(c.name, c.m0, c.m1, c.where);
          } else {
            call(c);
          }
        },
        rc);
  }
}

}  // namespace lantern::pbrt
