// Errors and warnings reported to the user, always with a place to look.
#pragma once

#include <functional>
#include <stdexcept>
#include <string>
#include <string_view>

namespace lantern {

// Input bytes as they may appear in a message: at most max_chars of them,
// with control and non-ASCII bytes written as \xNN, so a message about a
// binary or mis-encoded file is itself readable text.
inline std::string printable(std::string_view bytes, size_t max_chars = 40) {
  static const char* hex = "0123456789abcdef";
  std::string out;
  for (size_t i = 0; i < bytes.size() && i < max_chars; ++i) {
    unsigned char c = (unsigned char)bytes[i];
    if (c >= 0x20 && c < 0x7f) {
      out += char(c);
    } else {
      out += "\\x";
      out += hex[c >> 4];
      out += hex[c & 15];
    }
  }
  if (bytes.size() > max_chars) out += "...";
  return out;
}

struct SourceLocation {
  std::string file;
  int line = 0;
  int column = 0;

  std::string str() const {
    if (file.empty()) return "<input>";
    std::string s = printable(file, 1024);  // a path, unless the input is hostile
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
