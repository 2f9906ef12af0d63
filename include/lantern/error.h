// Errors and warnings reported to the user, always with a place to look.
#pragma once

#include <functional>
#include <stdexcept>
#include <string>

namespace lantern {

struct SourceLocation {
  std::string file;
  int line = 0;
  int column = 0;

  std::string str() const {
    if (file.empty()) return "<input>";
    std::string s = file;
    if (line > 0) s += ":" + std::to_string(line);
    if (column > 0) s += ":" + std::to_string(column);
    return s;
  }
};

// A problem with the user's input: the message starts with file:line:col.
class InputError : public std::runtime_error {
 public:
  InputError(const SourceLocation& where, const std::string& what)
      : std::runtime_error(where.str() + ": error: " + what), location(where) {}
  SourceLocation location;
};

using WarningSink = std::function<void(const std::string&)>;

}  // namespace lantern
