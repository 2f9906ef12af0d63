// Perlin's gradient noise (K. Perlin, "Improving Noise", SIGGRAPH 2002: his
// reference permutation, gradient set and quintic fade) and the textures
// pbrt-v4 builds from it: fbm, wrinkled (turbulence), windy and marble
// (Pharr, Jakob & Humphreys, PBR 4th ed., sec. 10.6). As there, octaves
// finer than the pixel's footprint are left out (fbm) or stood in for by
// their average (turbulence), with a smooth fade over the last one.
#pragma once

#include "math/common.h"

namespace lantern {

float perlin_noise(Vec3 p);
inline float perlin_noise(float x, float y) { return perlin_noise(Vec3(x, y, 0.5f)); }

// Sums of octaves with frequencies growing by 1.99 and weights by omega;
// dpdx, dpdy: the footprint in the noise's space (zero: every octave).
float fbm(Vec3 p, Vec3 dpdx, Vec3 dpdy, float omega, int octaves);
float turbulence(Vec3 p, Vec3 dpdx, Vec3 dpdy, float omega, int octaves);

float windy(Vec3 p, Vec3 dpdx, Vec3 dpdy);
RGB marble(Vec3 p, Vec3 dpdx, Vec3 dpdy, float omega, int octaves, float scale, float variation);

}  // namespace lantern
