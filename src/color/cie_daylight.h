// CIE daylight (the D series) at any chromaticity on the daylight locus:
// the mean daylight S0 plus M1 and M2 times its first two characteristic
// vectors S1 and S2 (Judd, MacAdam and Wyszecki 1964; CIE 015:2004,
// sec. 3.1 and Table T.2, 10 nm from 300 to 830 nm), linear between the
// table's entries and zero outside it. 100 at 560 nm, where S1 and S2 are
// zero, whatever the chromaticity.
//
// It gives the whites that no measured table here holds: ACES's (SMPTE ST
// 2065-1: daylight of chromaticity 0.32168, 0.33767, about 6000 K), which
// pbrt-v4 calls "illum-acesD60" and makes the white of "aces2065-1", and
// CIE D50 ("stdillum-D50").
#pragma once

#include "math/common.h"

namespace lantern {

// The weights of S1 and S2 (CIE 015:2004, eq. 3.6) for the daylight of
// CIE xy chromaticity `white`, and the daylight they give at wavelength nm.
struct DaylightWeights {
  double m1, m2;
};
DaylightWeights daylight_weights(Vec2 white);
double cie_daylight(double nm, DaylightWeights w);

// ACES's white, SMPTE ST 2065-1's chromaticity.
inline constexpr Vec2 kAcesWhite{0.32168f, 0.33767f};
float aces_d60(float nm);

// CIE D50: the daylight of 5000 K on the CIE 1931 scale of the second
// radiation constant c2 = 1.4388e-2 m K, that is 5000 * 1.4388 / 1.438 K
// on the scale the daylight locus is written in (CIE 015:2004, note 4 of
// sec. 3.1). M1 and M2 are rounded to three decimals, as the CIE did for
// its tables.
float cie_d50(float nm);

}  // namespace lantern
