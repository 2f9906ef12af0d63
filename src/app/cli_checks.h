// Command-line value checks that say what was expected in words
// ("--spp: must be a positive integer, not "-3"") rather than as a numeric
// range with the largest double written out.
#pragma once

#include <CLI/CLI.hpp>

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <string>

namespace lantern::cli {

// An integer in [lo, hi], written in full (no trailing characters).
inline CLI::Validator integer_in(long long lo, long long hi, const std::string& expected) {
  return CLI::Validator(
      [=](std::string& s) -> std::string {
        errno = 0;
        char* end = nullptr;
        const long long v = std::strtoll(s.c_str(), &end, 10);
        if (s.empty() || *end != '\0' || errno == ERANGE || v < lo || v > hi)
          return "must be " + expected + ", not \"" + s + "\"";
        return {};
      },
      "");
}

// A finite number above lo (or at least lo when `inclusive`) and at most hi.
inline CLI::Validator number_in(double lo, double hi, bool inclusive, const std::string& expected) {
  return CLI::Validator(
      [=](std::string& s) -> std::string {
        errno = 0;
        char* end = nullptr;
        const double v = std::strtod(s.c_str(), &end);
        const bool above = inclusive ? v >= lo : v > lo;
        if (s.empty() || *end != '\0' || errno == ERANGE || !std::isfinite(v) || !above || v > hi)
          return "must be " + expected + ", not \"" + s + "\"";
        return {};
      },
      "");
}

// "K/N" with 1 <= K <= N <= 1000000: part K of a render split into N.
inline bool parse_part(const std::string& s, long long& k, long long& n) {
  errno = 0;
  char* end = nullptr;
  k = std::strtoll(s.c_str(), &end, 10);
  if (end == s.c_str() || *end != '/' || errno == ERANGE) return false;
  const char* rest = end + 1;
  n = std::strtoll(rest, &end, 10);
  return end != rest && *end == '\0' && errno != ERANGE && k >= 1 && n >= k && n <= 1000000;
}
inline CLI::Validator part_of() {
  return CLI::Validator(
      [](std::string& s) -> std::string {
        long long k = 0, n = 0;
        if (!parse_part(s, k, n)) return "must be K/N with 1 <= K <= N <= 1000000 (part K of N), not \"" + s + "\"";
        return {};
      },
      "");
}

inline CLI::Validator positive_integer() { return integer_in(1, 2147483647, "a positive integer"); }
inline CLI::Validator positive_seconds() { return number_in(0.0, HUGE_VAL, false, "a positive number of seconds"); }

}  // namespace lantern::cli
