// The parser's parameter lists: "type name" [values], each checked
// against its declared type as it is read.
#include <algorithm>

#include "scene/pbrt/parser_core.h"

namespace lantern::pbrt {

// --- parameter lists -------------------------------------------------------

// The directive's parameters, then the defaults an Attribute gave for its
// kind (`attributes`: "shape", "light", ...) where it gives none of the
// same name. The defaults count as used: as in pbrt-v4, one that a
// directive does not read is no warning.
// kind: the directive's (pbrt/known_params.h).
ParamSet Parser::params(const Token& at, const std::string& directive, const char* kind, const char* attributes) {
  ParamSet ps = own_params(at, directive);
  ps.kind = kind;
  if (!attributes) return ps;
  auto it = gs_.attributes.find(attributes);
  if (it == gs_.attributes.end()) return ps;
  for (const Param& a : it->second)
    if (std::none_of(ps.params.begin(), ps.params.end(), [&](const Param& p) { return p.name == a.name; })) {
      ps.params.push_back(a);
      ps.params.back().used = true;
    }
  return ps;
}

ParamSet Parser::own_params(const Token& at, const std::string& directive) {
  ParamSet ps;
  ps.where = loc(at);
  ps.directive = directive;
  ps.base_dir = base_dir_;
  ps.warn = &warn_sink_;
  ps.lenient = b_->lenient();
  ps.color_space = gs_.color_space;
  while (peek().kind == TokenKind::String) {
    Token decl = next();
    Param p;
    p.where = loc(decl);
    std::string s = unescape(decl.text);
    size_t a = s.find_first_not_of(" \t"), sp = s.find_first_of(" \t", a);
    size_t c = sp == std::string::npos ? sp : s.find_first_not_of(" \t", sp);
    if (a == std::string::npos || c == std::string::npos)
      fail(decl, "expected a parameter declaration \"type name\", found \"" + printable(s) + "\"");
    p.type = s.substr(a, sp - a);
    p.name = s.substr(c, s.find_last_not_of(" \t") - c + 1);
    static const char* kTypes[] = {"integer", "float",  "point2", "vector2", "point3",    "vector3", "normal",
                                   "normal3", "point",  "vector", "color",   "rgb",       "spectrum", "blackbody",
                                   "bool",    "string", "texture"};
    bool known = false;
    for (const char* k : kTypes) known |= p.type == k;
    if (!known) fail(decl, "unknown parameter type \"" + p.type + "\" in \"" + printable(s) + "\"");
    values(p, decl);
    for (const Param& q : ps.params)
      if (q.name == p.name) fail(decl, "parameter \"" + printable(p.name) + "\" is given twice");
    ps.params.push_back(std::move(p));
  }
  return ps;
}

void Parser::value(Param& p, const Token& v) {
  bool stringy = p.type == "string" || p.type == "texture" || p.type == "bool" || p.type == "spectrum";
  if (v.kind == TokenKind::Number) {
    if (p.type == "string" || p.type == "texture" || p.type == "bool")
      fail(v, "parameter \"" + printable(p.name) + "\" of type \"" + p.type + "\" expects quoted strings, found a number");
    p.numbers.push_back(to_number(v));
  } else if (v.kind == TokenKind::String || (p.type == "bool" && v.kind == TokenKind::Identifier)) {
    if (!stringy) fail(v, "parameter \"" + printable(p.name) + "\" of type \"" + p.type + "\" expects numbers, found a string" + describe(v));
    std::string s = unescape(v.text);
    if (p.type == "bool") {
      if (s != "true" && s != "false") fail(v, "parameter \"" + printable(p.name) + "\" expects true or false, found \"" + printable(s) + "\"");
      p.bools.push_back(s == "true");
    } else {
      p.strings.push_back(std::move(s));
    }
  } else {
    fail(v, "expected a value for parameter \"" + printable(p.name) + "\", found " + token_kind_name(v.kind) + describe(v));
  }
}

void Parser::values(Param& p, const Token& decl) {
  Token t = next();
  if (t.kind != TokenKind::OpenBracket) {
    value(p, t);
    return;
  }
  for (;;) {
    Token v = next();
    if (v.kind == TokenKind::CloseBracket) break;
    if (v.kind == TokenKind::End) fail(decl, "the file ended inside the value list of \"" + printable(p.name) + "\" (missing ']')");
    value(p, v);
  }
}

void Parser::values_skip() {
  next();
  for (Token v = next(); v.kind != TokenKind::CloseBracket; v = next())
    if (v.kind == TokenKind::End) fail(v, "the file ended inside a value list (missing ']')");
}

}  // namespace lantern::pbrt
