#include "scene/pbrt/tokenizer.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <cerrno>
#include <filesystem>

namespace lantern::pbrt {

Tokenizer::Tokenizer(std::string text, std::string filename) : owned_(std::move(text)), filename_(std::move(filename)) {
  text_ = owned_;
}

Tokenizer::Tokenizer(std::unique_ptr<char[]> text, size_t size, std::string filename)
    : buffer_(std::move(text)), text_(buffer_.get(), size), filename_(std::move(filename)) {}

Tokenizer::~Tokenizer() = default;

std::unique_ptr<Tokenizer> Tokenizer::from_file(const std::string& path, const SourceLocation& from) {
  // Only regular files: a name such as /dev/zero or a FIFO would never end.
  std::error_code ec;
  if (std::filesystem::exists(path, ec) && !std::filesystem::is_regular_file(path, ec))
    throw InputError(from, "scene file \"" + printable(path, 200) + "\" is not a regular file");
  // One read into a buffer of the file's size, not zeroed first: a file of
  // millions of placements is hundreds of megabytes (docs/performance.md,
  // "Production scale"). (A mapping would save the copy too, but a file
  // cut short while mapped kills the process.)
  const int fd = open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) throw InputError(from, "cannot open scene file \"" + printable(path, 200) + "\"");
  struct stat st {};
  const size_t size = fstat(fd, &st) == 0 ? size_t(std::max<off_t>(st.st_size, 0)) : 0;
  std::unique_ptr<char[]> buf(new char[size]);
  size_t got = 0;
  while (got < size) {  // a file that shrinks meanwhile is parsed as far as it goes
    const ssize_t r = read(fd, buf.get() + got, size - got);
    if (r < 0 && errno == EINTR) continue;
    if (r < 0) {
      close(fd);
      throw InputError(from, "cannot read scene file \"" + printable(path, 200) + "\"");
    }
    if (r == 0) break;
    got += size_t(r);
  }
  close(fd);
  return std::unique_ptr<Tokenizer>(new Tokenizer(std::move(buf), got, path));
}

void Tokenizer::fail(int line, int col, const std::string& what) const {
  throw InputError({filename_, line, col}, what);
}

namespace {

// Character classes, looked up: the tokenizer's inner loops run over
// gigabytes of text in a production scene.
enum : uint8_t { kSpace = 1, kDelimiter = 2, kWord = 4 };
constexpr std::array<uint8_t, 256> kClasses = [] {
  std::array<uint8_t, 256> c{};
  for (unsigned char s : {' ', '\t', '\r', '\n', '\f', '\v'}) c[s] = kSpace | kDelimiter;
  for (unsigned char d : {'"', '[', ']', '#'}) c[d] = kDelimiter;
  for (int i = 0; i < 256; ++i)
    if ((i >= 'a' && i <= 'z') || (i >= 'A' && i <= 'Z') || (i >= '0' && i <= '9') || i == '_') c[size_t(i)] = kWord;
  return c;
}();
bool is_space(char c) { return kClasses[uint8_t(c)] & kSpace; }
bool is_delimiter(char c) { return kClasses[uint8_t(c)] & kDelimiter; }
bool is_word(char c) { return kClasses[uint8_t(c)] & kWord; }

}  // namespace

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
  t.source = this;
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
      if (!is_word(ch)) {
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
