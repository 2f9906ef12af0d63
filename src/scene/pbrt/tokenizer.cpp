#include "scene/pbrt/tokenizer.h"

#include <filesystem>
#include <fstream>

namespace lantern::pbrt {

Tokenizer::Tokenizer(std::string text, std::string filename)
    : text_(std::move(text)), filename_(std::move(filename)) {}

std::unique_ptr<Tokenizer> Tokenizer::from_file(const std::string& path, const SourceLocation& from) {
  // Only regular files: a name such as /dev/zero or a FIFO would never end.
  std::error_code ec;
  if (std::filesystem::exists(path, ec) && !std::filesystem::is_regular_file(path, ec))
    throw InputError(from, "scene file \"" + printable(path, 200) + "\" is not a regular file");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(from, "cannot open scene file \"" + printable(path, 200) + "\"");
  // Read straight into a string of the file's size: a stream buffer and
  // its copy would hold three times a file of millions of placements.
  std::string text;
  const auto size = std::filesystem::file_size(path, ec);
  if (!ec) {
    text.resize(size);
    in.read(text.data(), std::streamsize(size));
    text.resize(size_t(in.gcount()));
  }
  if (in.bad() || ec) throw InputError(from, "cannot read scene file \"" + printable(path, 200) + "\"");
  return std::make_unique<Tokenizer>(std::move(text), path);
}

void Tokenizer::fail(int line, int col, const std::string& what) const {
  throw InputError({filename_, line, col}, what);
}

static bool is_space(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\n' || c == '\f' || c == '\v'; }
static bool is_delimiter(char c) { return is_space(c) || c == '"' || c == '[' || c == ']' || c == '#'; }

Token Tokenizer::next() {
  const size_t n = text_.size();
  for (;;) {
    while (pos_ < n && is_space(text_[pos_])) {
      if (text_[pos_] == '\n') {
        ++line_;
        line_start_ = pos_ + 1;
      }
      ++pos_;
    }
    if (pos_ < n && text_[pos_] == '#') {
      while (pos_ < n && text_[pos_] != '\n') ++pos_;
      continue;
    }
    break;
  }
  Token t;
  t.line = line_;
  t.column = int(pos_ - line_start_) + 1;
  if (pos_ >= n) return t;

  char c = text_[pos_];
  if (c == '[' || c == ']') {
    t.kind = c == '[' ? TokenKind::OpenBracket : TokenKind::CloseBracket;
    t.text = std::string_view(text_).substr(pos_, 1);
    ++pos_;
    return t;
  }
  if (c == '"') {
    size_t start = ++pos_;
    while (pos_ < n && text_[pos_] != '"') {
      if (text_[pos_] == '\n') fail(t.line, t.column, "unterminated string: a newline came before the closing '\"'");
      if (text_[pos_] == '\\') ++pos_;
      ++pos_;
    }
    if (pos_ >= n) fail(t.line, t.column, "unterminated string: the file ended before the closing '\"'");
    t.kind = TokenKind::String;
    t.text = std::string_view(text_).substr(start, pos_ - start);
    ++pos_;
    return t;
  }
  size_t start = pos_;
  while (pos_ < n && !is_delimiter(text_[pos_])) ++pos_;
  t.text = std::string_view(text_).substr(start, pos_ - start);
  char f = t.text[0];
  bool numeric = (f >= '0' && f <= '9') || f == '-' || f == '+' || f == '.';
  t.kind = numeric ? TokenKind::Number : TokenKind::Identifier;
  if (!numeric) {
    for (char ch : t.text) {
      bool ok = (ch >= 'a' && ch <= 'z') || (ch >= 'A' && ch <= 'Z') || (ch >= '0' && ch <= '9') || ch == '_';
      if (!ok) {
        fail(t.line, t.column, "unexpected characters \"" + printable(t.text) + "\": expected a directive name, a number, a quoted string or '[' / ']'");
      }
    }
  }
  return t;
}

std::string unescape(std::string_view s) {
  std::string out;
  out.reserve(s.size());
  for (size_t i = 0; i < s.size(); ++i) {
    if (s[i] != '\\' || i + 1 == s.size()) {
      out += s[i];
      continue;
    }
    char e = s[++i];
    switch (e) {
      case 'n': out += '\n'; break;
      case 't': out += '\t'; break;
      case 'b': out += '\b'; break;
      case 'f': out += '\f'; break;
      case 'r': out += '\r'; break;
      default: out += e; break;
    }
  }
  return out;
}

const char* token_kind_name(TokenKind k) {
  switch (k) {
    case TokenKind::Identifier: return "a directive name";
    case TokenKind::String: return "a quoted string";
    case TokenKind::Number: return "a number";
    case TokenKind::OpenBracket: return "'['";
    case TokenKind::CloseBracket: return "']'";
    case TokenKind::End: return "the end of the file";
  }
  return "?";
}

}  // namespace lantern::pbrt
