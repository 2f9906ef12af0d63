// The CIE 1931 2-degree standard colorimetric observer, tabulated, and the
// colours of spectra integrated against it: what turns pbrt's spectral
// parameters (blackbody emitters) into Lantern's linear sRGB.
#pragma once

#include "math/common.h"

namespace lantern {

// x-bar, y-bar, z-bar at wavelength nm: linear between the 5 nm entries of
// the table (CIE 015:2004, Table T.4), zero outside 380-780 nm.
Vec3 cie1931_cmf(float nm);

// CIE XYZ of a black body at `kelvin` (Planck's law, integrated over
// 380-780 nm at 1 nm against the table), scaled to Y = 1.
Vec3 blackbody_xyz(float kelvin);

// XYZ to linear sRGB (IEC 61966-2-1, D65 white).
inline RGB xyz_to_linear_srgb(const Vec3& xyz) {
  return RGB(3.2404542f * xyz.x - 1.5371385f * xyz.y - 0.4985314f * xyz.z,
             -0.9692660f * xyz.x + 1.8760108f * xyz.y + 0.0415560f * xyz.z,
             0.0556434f * xyz.x - 0.2040259f * xyz.y + 1.0572252f * xyz.z);
}

}  // namespace lantern
