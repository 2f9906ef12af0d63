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

inline CLI::Validator positive_integer() { return integer_in(1, 2147483647, "a positive integer"); }
inline CLI::Validator positive_seconds() { return number_in(0.0, HUGE_VAL, false, "a positive number of seconds"); }

}  // namespace lantern::cli
