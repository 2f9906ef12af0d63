// What the command line says, by level (--log-level) and where
// (--log-file): errors, warnings, the progress line and the summary
// (info, the default), and what loading and rendering did, step by step
// (verbose). One place decides, so that a progress line rewritten in place
// on a terminal is never broken by a warning from another thread.
#pragma once

#include <string>

namespace lantern::logging {

enum class Level { Error = 0, Warning = 1, Info = 2, Verbose = 3 };

// "error", "warning", "info", "verbose"; pbrt-v4's "fatal" is "error".
// Throws std::invalid_argument for another word.
Level parse_level(const std::string& word);

// At most `level` from now on; with a file, messages go to it (appended)
// instead of standard error, and errors to both. Throws
// std::runtime_error naming the file when it cannot be opened.
void configure(Level level, const std::string& file = "");
bool enabled(Level level);
// Whether progress may be rewritten in place: messages go to standard
// error, and it is a terminal.
bool terminal();

// One message, a line of its own ("warning: " and "error: " are the
// caller's, as the scene loader writes its own locations before them).
void line(Level level, const std::string& text);
void error(const char* format, ...) __attribute__((format(printf, 1, 2)));
void warning(const char* format, ...) __attribute__((format(printf, 1, 2)));
void info(const char* format, ...) __attribute__((format(printf, 1, 2)));
void verbose(const char* format, ...) __attribute__((format(printf, 1, 2)));

// The progress line (info): rewritten in place on a terminal, a whole line
// otherwise. A message in between starts on a line of its own.
void progress(const std::string& text);
// Ends a progress line left open on a terminal.
void end_progress();

}  // namespace lantern::logging
