// Errors and warnings reported to the user, always with a place to look.
#pragma once

#include <functional>
#include <memory>
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

// A file's name, shared by the locations in it: a location is copied for
// each of the millions of placements of a production scene, and a copy
// here allocates nothing.
class FileName {
 public:
  FileName() = default;
  FileName(std::string s) : s_(s.empty() ? nullptr : std::make_shared<const std::string>(std::move(s))) {}
  FileName(const char* s) : FileName(std::string(s)) {}
  const std::string& str() const {
    static const std::string kNone;
    return s_ ? *s_ : kNone;
  }
  operator const std::string&() const { return str(); }
  bool empty() const { return !s_; }
  friend bool operator==(const FileName& a, const FileName& b) { return a.s_ == b.s_ || a.str() == b.str(); }

 private:
  std::shared_ptr<const std::string> s_;
};

struct SourceLocation {
  FileName file;
  int line = 0;
  int column = 0;

  std::string str() const {
    if (file.empty()) return "<input>";
    std::string s = printable(file.str(), 1024);  // a path, unless the input is hostile
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
