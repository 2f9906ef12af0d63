#include "trace/timeline.h"

#include <algorithm>
#include <cinttypes>
#include <cstdio>

namespace lantern {

TraceBuffer::TraceBuffer(Timeline* owner, uint32_t track, std::string name)
    : owner_(owner), track_(track), name_(std::move(name)) {
  paths_alive_ = owner->intern("paths alive (" + name_ + ")");
  rays_per_query_ = owner->intern("rays per query (" + name_ + ")");
}

void TraceBuffer::begin_wave(int64_t wave) {
  wave_ = wave;
  full_ = owner_->keeps(wave);
  if (!full_) ++dropped_waves_;
}

void TraceBuffer::span(const char* name, TraceCategory category, TraceClock::time_point begin,
                       TraceClock::time_point end, int64_t value) {
  if (!full_) {
    ++dropped_;
    return;
  }
  const int64_t b = owner_->ns(begin);
  events_.push_back({name, category, 'X', b, std::max<int64_t>(owner_->ns(end) - b, 0), wave_, value});
}

void TraceBuffer::counter(const char* name, TraceClock::time_point at, int64_t value, bool always) {
  if (!full_ && !always) return;
  events_.push_back({name, TraceCategory::Pipeline, 'C', owner_->ns(at), 0, wave_, value});
}

Timeline::Timeline(uint64_t full_waves)
    : origin_(TraceClock::now()),
      full_waves_(full_waves),
      main_(this, 0, "main"),
      pipeline_(this, 1, "serial stage: film merge"),
      workers_([this] {
        const uint32_t track = next_track_++;
        return TraceBuffer(this, track, "worker " + std::to_string(track - 1));
      }) {}

TraceBuffer& Timeline::local() { return workers_.local(); }

const char* Timeline::intern(const std::string& name) {
  std::lock_guard<std::mutex> lock(names_mutex_);
  names_.push_back(name);
  return names_.back().c_str();
}

namespace {

const char* category_name(TraceCategory c) {
  static const char* names[] = {"wave", "stage", "rays", "pipeline", "load", "render", "output"};
  return names[int(c)];
}

// Names are the project's own (static or interned); only quotes and
// backslashes need escaping, and control characters are dropped.
std::string escaped(const char* s) {
  std::string out;
  for (; *s; ++s) {
    if (*s == '"' || *s == '\\') out += '\\';
    if (static_cast<unsigned char>(*s) >= 0x20) out += *s;
  }
  return out;
}

void append_event(std::string& out, const TraceEvent& e, uint32_t track) {
  char buf[512];
  const std::string name = escaped(e.name);
  if (e.phase == 'C') {
    std::snprintf(buf, sizeof buf,
                  "{\"name\":\"%s\",\"ph\":\"C\",\"ts\":%.3f,\"pid\":1,\"tid\":%u,\"args\":{\"value\":%" PRId64 "}}",
                  name.c_str(), double(e.begin_ns) * 1e-3, track, e.value);
  } else {
    int n = std::snprintf(buf, sizeof buf,
                          "{\"name\":\"%s\",\"cat\":\"%s\",\"ph\":\"X\",\"ts\":%.3f,\"dur\":%.3f,\"pid\":1,\"tid\":%u,"
                          "\"args\":{",
                          name.c_str(), category_name(e.category), double(e.begin_ns) * 1e-3,
                          double(e.duration_ns) * 1e-3, track);
    const char* sep = "";
    if (e.wave >= 0) n += std::snprintf(buf + n, sizeof buf - size_t(n), "\"wave\":%" PRId64, e.wave), sep = ",";
    if (e.value >= 0) {
      const char* key = e.category == TraceCategory::Rays   ? "rays"
                        : e.category == TraceCategory::Wave ? "paths"
                                                            : "value";
      n += std::snprintf(buf + n, sizeof buf - size_t(n), "%s\"%s\":%" PRId64, sep, key, e.value);
    }
    std::snprintf(buf + n, sizeof buf - size_t(n), "}}");
  }
  out += buf;
}

}  // namespace

std::string Timeline::json() const {
  std::vector<const TraceBuffer*> tracks = {&main_, &pipeline_};
  for (const TraceBuffer& b : workers_) tracks.push_back(&b);
  std::sort(tracks.begin() + 2, tracks.end(), [](auto* a, auto* b) { return a->track() < b->track(); });
  uint64_t dropped_spans = 0;
  for (const TraceBuffer* t : tracks) dropped_spans += t->dropped_spans();
  const uint64_t dropped_waves = pipeline_.dropped_waves();  // the merge sees every wave once

  std::string out = "{\"displayTimeUnit\":\"ms\",\"otherData\":{\"producer\":\"lantern\",";
  out += "\"waves_kept_in_full\":\"" + (full_waves_ == 0 ? std::string("all") : std::to_string(full_waves_)) + "\",";
  out += "\"waves_dropped\":" + std::to_string(dropped_waves) + ",\"spans_dropped\":" + std::to_string(dropped_spans);
  out +=
      ",\"note\":\"waves past the first waves_kept_in_full keep only the film-merge queue counter; their "
      "spans are dropped\"},\n\"traceEvents\":[\n";
  out += "{\"name\":\"process_name\",\"ph\":\"M\",\"pid\":1,\"args\":{\"name\":\"lantern\"}}";
  for (const TraceBuffer* t : tracks) {
    out += ",\n{\"name\":\"thread_name\",\"ph\":\"M\",\"pid\":1,\"tid\":" + std::to_string(t->track()) +
           ",\"args\":{\"name\":\"" + escaped(t->name().c_str()) + "\"}}";
    out += ",\n{\"name\":\"thread_sort_index\",\"ph\":\"M\",\"pid\":1,\"tid\":" + std::to_string(t->track()) +
           ",\"args\":{\"sort_index\":" + std::to_string(t->track()) + "}}";
  }
  for (const TraceBuffer* t : tracks)
    for (const TraceEvent& e : t->events()) {
      out += ",\n";
      append_event(out, e, t->track());
    }
  out += "\n]}\n";
  return out;
}

}  // namespace lantern
