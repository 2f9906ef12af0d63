// Splits pbrt scene text into tokens, each with its file, line and column.
#pragma once

#include <memory>
#include <string>
#include <string_view>

#include "lantern/error.h"

namespace lantern::pbrt {

enum class TokenKind { Identifier, String, Number, OpenBracket, CloseBracket, End };

class Tokenizer;

struct Token {
  TokenKind kind = TokenKind::End;
  const Tokenizer* source = nullptr;  // the file it comes from
  std::string_view text;  // for strings: without the quotes, escapes unresolved
  int line = 0;
  int column = 0;
};

class Tokenizer {
 public:
  // Owns the text of one file.
  Tokenizer(std::string text, std::string filename);
  static std::unique_ptr<Tokenizer> from_file(const std::string& path, const SourceLocation& included_from);
  ~Tokenizer();
  Tokenizer(const Tokenizer&) = delete;
  Tokenizer& operator=(const Tokenizer&) = delete;

  Token next();
  const std::string& filename() const { return filename_.str(); }
  size_t size() const { return text_.size(); }
  SourceLocation location(const Token& t) const { return {filename_, t.line, t.column}; }

 private:
  Tokenizer(std::unique_ptr<char[]> text, size_t size, std::string filename);
  [[noreturn]] void fail(int line, int col, const std::string& what) const;
  std::string owned_;               // the text given, or
  std::unique_ptr<char[]> buffer_;  // the file's
  std::string_view text_;
  FileName filename_;
  size_t pos_ = 0;
  int line_ = 1;
  size_t line_start_ = 0;
};

// Resolves backslash escapes inside a quoted string token.
std::string unescape(std::string_view s);
const char* token_kind_name(TokenKind k);

}  // namespace lantern::pbrt
