// Perlin's gradient noise (K. Perlin, "Improving Noise", SIGGRAPH 2002: his
// reference permutation, gradient set and quintic fade) and the textures
// pbrt-v4 builds from it: fbm, wrinkled (turbulence), windy and marble
// (Pharr, Jakob & Humphreys, PBR 4th ed., sec. 10.6). Lantern has no ray
// differentials yet, so every octave is summed: pbrt-v4 drops the octaves
// finer than a pixel's footprint, which changes detail, not the mean.
#pragma once

#include "math/common.h"

namespace lantern {

float perlin_noise(Vec3 p);
inline float perlin_noise(float x, float y) { return perlin_noise(Vec3(x, y, 0.5f)); }

// Sums of octaves with frequencies growing by 1.99 and weights by omega.
float fbm(Vec3 p, float omega, int octaves);
float turbulence(Vec3 p, float omega, int octaves);

float windy(Vec3 p);
RGB marble(Vec3 p, float omega, int octaves, float scale, float variation);

}  // namespace lantern
