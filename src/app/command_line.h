// Parsing the command line as a tool run in batches needs: a usage error
// exits with 2 (docs/cli.md's table of exit codes) and says what was meant
// when a flag or subcommand is a near miss ("--sp": did you mean "--spp"?).
#pragma once

#include <CLI/CLI.hpp>

#include <stdexcept>

#include "app/render_request.h"

namespace lantern::cli {

// A command line asking for what cannot be (a value out of range found
// after parsing, such as a pixel outside the image): exit 2, as a usage
// error.
struct UsageError : std::invalid_argument {
  using std::invalid_argument::invalid_argument;
};

// Parses argv into app; -1 when parsing succeeded (go on), otherwise the
// exit code (0 after --help or --version, 2 after a usage error).
int parse_command_line(CLI::App& app, int argc, char** argv);

// The closest of `candidates` to `word` within an edit distance of
// max(2, size / 3), or "" when none is that close.
std::string closest(const std::string& word, const std::vector<std::string>& candidates);

// The options of a RenderRequest (--spp, --integrator, --maxdepth, ...),
// for every subcommand that renders (render, view).
void add_render_request_options(CLI::App& c, RenderRequest& r);

}  // namespace lantern::cli
