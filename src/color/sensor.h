// The film's sensor as pbrt-v4's RGB film defines it for its "cie1931"
// sensor (its default): the CIE 1931 observer, white-balanced, scaled by
// the imaging ratio. Every sample's colour passes through it.
#pragma once

#include "color/color_space.h"

namespace lantern {

struct SensorSettings {
  float iso = 100.f;           // Film "iso"
  float exposure_time = 1.f;   // Camera "shutterclose" - "shutteropen"
  float whitebalance = 0.f;    // Film "whitebalance" (kelvin; 0: none)
  const ColorSpace* output = nullptr;  // the image's colour space (null: sRGB)
};

// The sensor as a matrix from the renderer's linear sRGB to the image's
// linear RGB: the imaging ratio, exposure time x ISO / 100 (1 by
// default), times a von Kries adaptation in Bradford's cone space from the
// white of `whitebalance` kelvin (CIE illuminant D at that temperature; a
// black body below 4000 K, where D is not defined) to the image space's
// white. Without white balance and in sRGB, a multiple of the identity.
Matrix3d sensor_matrix(const SensorSettings& s);

// exposure time x ISO / 100.
double imaging_ratio(const SensorSettings& s);

// The sensor's own RGB (before white balance and the output space) from
// the renderer's linear sRGB: for "cie1931", CIE XYZ times the imaging
// ratio. Film "maxcomponentvalue" clamps in it, as pbrt-v4 does.
Matrix3d sensor_rgb_matrix(const SensorSettings& s);

// The CIE xy chromaticity of CIE daylight illuminant D at nominal
// temperature kelvin (CIE 015:2004, eq. 3.3 and 3.4; the nominal
// temperature is the correlated colour temperature of the old value of
// the second radiation constant, 1.4380e-2 m K, so the CCT used is
// kelvin x 1.4388 / 1.4380), for 4000 to 25000 K.
Vec2 daylight_chromaticity(float kelvin);

}  // namespace lantern
