#include "app/log.h"

#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdarg>
#include <cstdio>
#include <cstring>
#include <mutex>
#include <stdexcept>
#include <vector>

namespace lantern::logging {

namespace {

struct State {
  std::mutex mutex;
  Level level = Level::Info;
  std::FILE* file = nullptr;  // --log-file, else messages go to stderr
  bool line_open = false;     // a progress line on the terminal, not ended
};

State& state() {
  static State s;
  return s;
}

std::FILE* out(const State& s) { return s.file ? s.file : stderr; }

// Under the lock.
void close_open_line(State& s) {
  if (!s.line_open) return;
  std::fputc('\n', stderr);
  s.line_open = false;
}

void write(Level level, const std::string& text) {
  State& s = state();
  if (level > s.level) return;
  std::lock_guard<std::mutex> lock(s.mutex);
  close_open_line(s);
  std::fprintf(out(s), "%s\n", text.c_str());
  std::fflush(out(s));
  if (level == Level::Error && s.file) std::fprintf(stderr, "%s\n", text.c_str());
}

std::string format(const char* f, va_list args) {
  va_list copy;
  va_copy(copy, args);
  const int n = std::vsnprintf(nullptr, 0, f, copy);
  va_end(copy);
  std::vector<char> buf(size_t(std::max(n, 0)) + 1);
  std::vsnprintf(buf.data(), buf.size(), f, args);
  return buf.data();
}

}  // namespace

Level parse_level(const std::string& w) {
  if (w == "error" || w == "fatal") return Level::Error;
  if (w == "warning") return Level::Warning;
  if (w == "info") return Level::Info;
  if (w == "verbose") return Level::Verbose;
  throw std::invalid_argument("--log-level: expected error, warning, info or verbose, not \"" + w + "\"");
}

void configure(Level level, const std::string& file) {
  State& s = state();
  std::lock_guard<std::mutex> lock(s.mutex);
  s.level = level;
  if (file.empty()) return;
  // Appended, never replaced: a log is often a file others write too, or a
  // pipe, and nothing in it is lost.
  std::FILE* f = std::fopen(file.c_str(), "a");
  if (!f) throw std::runtime_error("cannot open the log file " + file + ": " + std::strerror(errno));
  if (s.file) std::fclose(s.file);
  s.file = f;
}

bool enabled(Level level) { return level <= state().level; }

bool terminal() { return !state().file && isatty(STDERR_FILENO); }

void line(Level level, const std::string& text) { write(level, text); }

#define LANTERN_LOG_AT(name, level)           \
  void name(const char* f, ...) {             \
    if (!enabled(level)) return;              \
    va_list args;                             \
    va_start(args, f);                        \
    const std::string text = format(f, args); \
    va_end(args);                             \
    write(level, text);                       \
  }
LANTERN_LOG_AT(error, Level::Error)
LANTERN_LOG_AT(warning, Level::Warning)
LANTERN_LOG_AT(info, Level::Info)
LANTERN_LOG_AT(verbose, Level::Verbose)
#undef LANTERN_LOG_AT

void progress(const std::string& text) {
  State& s = state();
  if (Level::Info > s.level) return;
  std::lock_guard<std::mutex> lock(s.mutex);
  if (!s.file && isatty(STDERR_FILENO)) {
    std::fprintf(stderr, "\r\033[K%s", text.c_str());
    s.line_open = true;
  } else {
    std::fprintf(out(s), "%s\n", text.c_str());
  }
  std::fflush(out(s));
}

void end_progress() {
  State& s = state();
  std::lock_guard<std::mutex> lock(s.mutex);
  close_open_line(s);
}

}  // namespace lantern::logging
