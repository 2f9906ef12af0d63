// The CIE's standard fluorescent illuminants F1 to F12 (CIE 015:2004,
// Table T.6), which pbrt-v4 names "stdillum-F1" to "stdillum-F12": lamps
// whose smooth phosphor band carries the mercury lines at 405, 436, 546
// and 578 nm. F1-F6 are standard lamps, F7-F9 broadband, F10-F12
// three-band.
#pragma once

namespace lantern {

// Illuminant Fn (n from 1 to 12) at wavelength nm: the table's relative
// spectral power, linear between its 5 nm entries, zero outside 380-780 nm
// and for any other n.
float cie_fluorescent(int n, float nm);

}  // namespace lantern
