#pragma once

namespace lantern {

// IEEE 754's maxNum and minNum: the larger (the smaller) of a and b, the
// number where one of them is NaN, as std::fmax and std::fmin give it, and
// a where they are equal, as the C library here does, so that -0 and +0
// come out as before, bit for bit (tests/extremes_test.cpp, MaxNum). GCC
// calls the C library for std::fmax (no one instruction has its NaN rule):
// a call per use, in the hottest loops (light importance, roulette).
inline float max_num(float a, float b) { return a >= b || b != b ? a : b; }
inline float min_num(float a, float b) { return a <= b || b != b ? a : b; }
inline double max_num(double a, double b) { return a >= b || b != b ? a : b; }
inline double min_num(double a, double b) { return a <= b || b != b ? a : b; }

}  // namespace lantern
