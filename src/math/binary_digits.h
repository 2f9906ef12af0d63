// The binary digits of a number in [0, 1], for trees that halve the unit
// interval level by level (guiding's spatial and directional trees).
// Keeping the half that holds c and rescaling it, c -> 2c or 2c - 1, reads
// c's digits one by one, and those steps are exact in float; reading the
// digits from an integer instead costs a shift a level, not a dependent
// chain of float operations (docs/performance.md).
#pragma once

#include <cstdint>

namespace lantern {

// The first 32 digits below the point, the first at bit 31: all ones for
// 1 and above, none for 0, below it or NaN. Exact for the digits a float in
// [2^-8, 1) holds, and for the first 32 of any: enough for trees of at most
// 32 levels along one coordinate.
inline uint32_t binary_digits(float c) { return c >= 1.f ? 0xFFFFFFFFu : c > 0.f ? uint32_t(c * 0x1p32f) : 0u; }

}  // namespace lantern
