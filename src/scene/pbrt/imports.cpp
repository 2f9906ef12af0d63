// Include and Import: the parser's side (files resolved, cycles refused,
// Import'ed files parsed in place or on worker threads) and the queue that
// replays the worker threads' recordings in order.
#include "scene/pbrt/imports.h"

#include <filesystem>

#include "scene/pbrt/parser_core.h"

namespace lantern::pbrt {

namespace {

constexpr size_t kMaxIncludeDepth = 64;
// What a file parsed ahead may hold in recorded calls before its thread
// waits for the replay to catch up.
constexpr size_t kMaxRecordedBytes = size_t(512) << 20;

std::string canonical(const std::string& path) {
  std::error_code ec;
  return std::filesystem::weakly_canonical(path, ec).string();
}

// Forwards each call once the Imports before it are replayed.
class OrderedTarget final : public ParserTarget {
 public:
  OrderedTarget(ParserTarget& t, ImportQueue& q) : t_(t), q_(q) {}
  void warn(const SourceLocation& w, const std::string& s) const override { q_.drain(), t_.warn(w, s); }
  void warn_line(const std::string& l) const override { q_.drain(), t_.warn_line(l); }
  bool lenient() const override { return t_.lenient(); }
  void including(const std::string& p, size_t n) override { q_.drain(), t_.including(p, n); }
  void camera(const std::string& ty, const ParamSet& ps, const glm::dmat4& a, const glm::dmat4& b) override {
    q_.drain(), t_.camera(ty, ps, a, b);
  }
  void camera_medium(const std::string& n, const SourceLocation& w) override { q_.drain(), t_.camera_medium(n, w); }
  void film(const std::string& ty, const ParamSet& ps) override { q_.drain(), t_.film(ty, ps); }
  void sampler(const std::string& ty, const ParamSet& ps) override { q_.drain(), t_.sampler(ty, ps); }
  void integrator(const std::string& ty, const ParamSet& ps) override { q_.drain(), t_.integrator(ty, ps); }
  void pixel_filter(const std::string& ty, const ParamSet& ps) override { q_.drain(), t_.pixel_filter(ty, ps); }
  void begin_world(const glm::dmat4& m, double a, double b) override { q_.drain(), t_.begin_world(m, a, b); }
  MaterialHandle material(const std::string& ty, const ParamSet& ps, const std::map<std::string, MaterialHandle>& named,
                          const std::string& dir) override {
    q_.drain();
    return t_.material(ty, ps, named, dir);
  }
  void texture(const std::string& n, const std::string& v, const std::string& c, const ParamSet& ps, const Mat4& m,
               const std::string& dir) override {
    q_.drain(), t_.texture(n, v, c, ps, m, dir);
  }
  void shape(const std::string& ty, const ParamSet& ps, const GraphicsState& gs, const std::string& dir) override {
    q_.drain(), t_.shape(ty, ps, gs, dir);
  }
  void light(const std::string& ty, const ParamSet& ps, const Mat4& m, const std::string& dir, const std::string& med,
             const SourceLocation& w) override {
    q_.drain(), t_.light(ty, ps, m, dir, med, w);
  }
  void medium(const std::string& n, const ParamSet& ps, const Mat4& m, const std::string& dir) override {
    q_.drain(), t_.medium(n, ps, m, dir);
  }
  void begin_object(const std::string& n, const SourceLocation& w) override { q_.drain(), t_.begin_object(n, w); }
  void end_object(const SourceLocation& w) override { q_.drain(), t_.end_object(w); }
  void object_instance(const std::string& n, const glm::dmat4& a, const glm::dmat4& b,
                       const SourceLocation& w) override {
    q_.drain(), t_.object_instance(n, a, b, w);
  }

 private:
  ParserTarget& t_;
  ImportQueue& q_;
};

}  // namespace

// --- ImportQueue ---------------------------------------------------------------

struct ImportQueue::Job {
  CallStream stream{kMaxRecordedBytes};
  std::function<void(Recorder&)> parse;
};

ImportQueue::ImportQueue(ParserTarget& target, std::string base_dir, std::map<std::string, MaterialHandle>& named,
                         unsigned threads)
    : target_(target), base_dir_(std::move(base_dir)), named_(named), thread_count_(threads),
      ordered_(std::make_unique<OrderedTarget>(target, *this)) {}

ImportQueue::~ImportQueue() {
  cancel_all();
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stopping_ = true;
  }
  wake_.notify_all();
  for (std::thread& t : threads_) t.join();
}

void ImportQueue::submit(std::function<void(Recorder&)> parse) {
  auto job = std::make_shared<Job>();
  job->parse = std::move(parse);
  order_.push_back(job);
  {
    std::lock_guard<std::mutex> lock(mutex_);
    waiting_.push_back(job);
  }
  wake_.notify_one();
  if (threads_.size() < thread_count_ && threads_.size() < order_.size()) threads_.emplace_back([this] { work(); });
}

void ImportQueue::work() {
  for (;;) {
    std::shared_ptr<Job> job;
    {
      std::unique_lock<std::mutex> lock(mutex_);
      wake_.wait(lock, [&] { return stopping_ || !waiting_.empty(); });
      if (waiting_.empty()) return;
      job = waiting_.front();
      waiting_.pop_front();
    }
    Recorder recorder(target_, job->stream);
    std::exception_ptr error;
    try {
      job->parse(recorder);
      recorder.flush();
    } catch (const RecordingCancelled&) {
    } catch (...) {
      // The calls before the error are replayed, then the error thrown.
      error = std::current_exception();
      try {
        recorder.flush();
      } catch (const RecordingCancelled&) {
      }
    }
    job->parse = nullptr;  // the parser and its file's text
    job->stream.finish(error);
  }
}

void ImportQueue::drain() {
  while (!order_.empty()) {
    std::shared_ptr<Job> job = order_.front();
    Replayer replayer(target_, &sink_, base_dir_, named_);
    std::vector<RecordedCall> calls;
    try {
      while (job->stream.pop(calls)) {
        replayer.replay(calls);
        job->stream.recycle(std::move(calls));
      }
    } catch (...) {
      cancel_all();
      throw;
    }
    order_.pop_front();
    if (std::exception_ptr e = job->stream.error()) {
      cancel_all();
      std::rethrow_exception(e);
    }
  }
}

void ImportQueue::cancel_all() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    waiting_.clear();
  }
  for (const std::shared_ptr<Job>& job : order_) job->stream.cancel();
  order_.clear();
}

// --- the parser's side ---------------------------------------------------------

Parser::Parser(const Parser& importer, bool names_at_replay)
    : b_(importer.b_), base_dir_(importer.base_dir_), gs_(importer.gs_), stack_(importer.stack_),
      stack_where_(importer.stack_where_), transform_only_(importer.transform_only_), named_cs_(importer.named_cs_),
      camera_from_world_(importer.camera_from_world_), render_from_world_(importer.render_from_world_),
      world_from_render_(importer.world_from_render_), transform_times_(importer.transform_times_),
      rendering_space_(importer.rendering_space_), in_world_(importer.in_world_),
      object_depth_(importer.object_depth_), ancestors_(importer.ancestors_), floor_(importer.stack_.size()),
      recorder_(importer.recorder_) {
  // A recorded file's material names are looked up at replay (parser.cpp).
  if (!names_at_replay) named_materials_ = importer.named_materials_;
  for (const auto& f : importer.files_) ancestors_.push_back(canonical(f->filename()));
}

std::string Parser::resolve(const Token& t, const std::string& file) const {
  std::filesystem::path p(file);
  if (!p.is_absolute() && !base_dir_.empty()) p = std::filesystem::path(base_dir_) / p;
  const std::string canon = canonical(p.string());
  bool cycle = std::find(ancestors_.begin(), ancestors_.end(), canon) != ancestors_.end();
  for (const auto& f : files_) cycle |= canonical(f->filename()) == canon;
  if (cycle) fail(t, std::string(t.text) + " cycle: \"" + printable(file) + "\" is already being read");
  if (files_.size() + ancestors_.size() >= kMaxIncludeDepth)
    fail(t, std::string(t.text) + " nested deeper than " + std::to_string(kMaxIncludeDepth) + " files");
  return p.string();
}

void Parser::include(const Token& t, const std::string& file) {
  const std::string path = resolve(t, file);
  if (peeked_) fail(t, "internal: Include with a pending token");
  files_.push_back(open(path, loc(t)));
}

std::unique_ptr<Tokenizer> Parser::open(const std::string& path, const SourceLocation& from) {
  auto file = Tokenizer::from_file(path, from);
  b_->including(file->filename(), file->size());
  return file;
}

// pbrt-v4's Import: the file starts from the graphics state here and its
// changes to it end with it; the materials it names, its objects, shapes
// and lights stay. Before WorldBegin, as Include (pbrt-v4 refuses it).
void Parser::import(const Token& t, const std::string& file) {
  if (!in_world_) return include(t, file);
  const std::string path = resolve(t, file);
  const SourceLocation from = loc(t);
  if (import_threads_ <= 1 || recorder_) {
    // In place, on this thread (and within a file being recorded).
    Parser child(*this, recorder_ != nullptr);
    child.run(child.open(path, from));
    if (!recorder_) named_materials_ = std::move(child.named_materials_);
    return;
  }
  if (!imports_) {
    imports_ = std::make_unique<ImportQueue>(*b_, base_dir_, named_materials_, import_threads_);
    b_ = &imports_->ordered();
  }
  auto child = std::make_shared<Parser>(*this, true);
  imports_->submit([child, path, from](Recorder& recorder) {
    child->b_ = &recorder;
    child->recorder_ = &recorder;
    child->run(child->open(path, from));
  });
}

void Parser::settle() {
  if (imports_) imports_->drain();
}

}  // namespace lantern::pbrt
