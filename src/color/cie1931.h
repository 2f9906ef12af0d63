// The CIE 1931 2-degree standard colorimetric observer, tabulated, and the
// colours of spectra integrated against it: what turns pbrt's spectral
// parameters (blackbody emitters) into Lantern's linear sRGB.
#pragma once

#include <functional>

#include "math/common.h"

namespace lantern {

// x-bar, y-bar, z-bar at wavelength nm: linear between the 5 nm entries of
// the table (CIE 015:2004, Table T.4), zero outside 380-780 nm.
Vec3 cie1931_cmf(float nm);

// Planck's law: a black body's spectral radiance at wavelength nm and
// temperature kelvin (W / (sr m^2 m)).
double blackbody_radiance(double nm, double kelvin);
// Its largest value over wavelength, at Wien's displacement-law peak: what
// pbrt-v4's BlackbodySpectrum divides by.
double blackbody_peak_radiance(double kelvin);

// CIE XYZ of a black body at `kelvin` (Planck's law, integrated over
// 380-780 nm at 1 nm against the table), scaled to Y = 1.
Vec3 blackbody_xyz(float kelvin);

// CIE XYZ of pbrt-v4's BlackbodySpectrum: Planck's law divided by its
// value at the peak wavelength (Wien's law), integrated against the table
// over wavelength in nm. This is what pbrt-v4's film records for it: its
// sensor integrates spectra against the matching functions without
// dividing by the integral of y-bar (its light spectra are normalised to
// a y-bar integral of 1 instead). Zero at or below 0 K.
Vec3 blackbody_peak_xyz(float kelvin);

// CIE standard illuminant D65's relative spectral power (100 at 560 nm):
// linear between the 5 nm entries of CIE 015:2004, Table T.1, zero outside
// 360-830 nm.
float cie_d65(float nm);

// Linear sRGB of a surface whose reflectance at each wavelength (nm) is
// `reflectance(nm)`, lit by D65, the sRGB white: integrated at 1 nm over
// 380-780 nm and normalised so that a constant reflectance c gives exactly
// (c, c, c). This is the colour a spectral renderer shows for the surface
// under a white (D65) light, which pbrt-v4's RGB lights are.
RGB reflectance_rgb(const std::function<double(double)>& reflectance);

// XYZ to linear sRGB (IEC 61966-2-1, D65 white).
inline RGB xyz_to_linear_srgb(const Vec3& xyz) {
  return RGB(3.2404542f * xyz.x - 1.5371385f * xyz.y - 0.4985314f * xyz.z,
             -0.9692660f * xyz.x + 1.8760108f * xyz.y + 0.0415560f * xyz.z,
             0.0556434f * xyz.x - 0.2040259f * xyz.y + 1.0572252f * xyz.z);
}

}  // namespace lantern
