#include "texture/noise.h"

#include <array>

namespace lantern {
namespace {

// Perlin's reference permutation of 0..255 (2002), repeated so that
// perm[perm[x] + y] never needs a wrap.
constexpr int kPermutation[256] = {151,160,137,91,90,15,131,13,201,95,96,53,194,233,7,225,140,36,103,30,69,142,8,99,37,240,21,10,23,190,6,148,247,120,234,75,0,26,197,62,94,252,219,203,117,35,11,32,57,177,33,88,237,149,56,87,174,20,125,136,171,168,68,175,74,165,71,134,139,48,27,166,77,146,158,231,83,111,229,122,60,211,133,230,220,105,92,41,55,46,245,40,244,102,143,54,65,25,63,161,1,216,80,73,209,76,132,187,208,89,18,169,200,196,135,130,116,188,159,86,164,100,109,198,173,186,3,64,52,217,226,250,124,123,5,202,38,147,118,126,255,82,85,212,207,206,59,227,47,16,58,17,182,189,28,42,223,183,170,213,119,248,152,2,44,154,163,70,221,153,101,155,167,43,172,9,129,22,39,253,19,98,108,110,79,113,224,232,178,185,112,104,218,246,97,228,251,34,242,193,238,210,144,12,191,179,162,241,81,51,145,235,249,14,239,107,49,192,214,31,181,199,106,157,184,84,204,176,115,121,50,45,127,4,150,254,138,236,205,93,222,114,67,29,24,72,243,141,128,195,78,66,215,61,156,180};

struct Permutation {
  std::array<int, 512> p;
  constexpr Permutation() : p() {
    for (int i = 0; i < 512; ++i) p[size_t(i)] = kPermutation[i & 255];
  }
};
constexpr Permutation kPerm;

// Dot product of the offset with one of 12 cube-edge gradients (16 entries,
// four repeated), chosen by the lattice point's hash h.
[[gnu::always_inline]] inline float grad(int h, float dx, float dy, float dz) {
  h &= 15;
  float u = h < 8 || h == 12 || h == 13 ? dx : dy;
  float v = h < 4 || h == 12 || h == 13 ? dy : dz;
  return ((h & 1) ? -u : u) + ((h & 2) ? -v : v);
}

float fade(float t) { return t * t * t * (t * (t * 6.f - 15.f) + 10.f); }
float lerp(float t, float a, float b) { return (1.f - t) * a + t * b; }

}  // namespace

float perlin_noise(Vec3 p) {
  // Keep the cell index within an int (fmod is slow, and the identity below).
  const float wrap = float(1 << 30);
  for (int k = 0; k < 3; ++k)
    if (!(std::fabs(p[k]) < wrap)) p[k] = std::fmod(p[k], wrap);
  if (!is_finite(p)) return 0.f;
  float fx = std::floor(p.x), fy = std::floor(p.y), fz = std::floor(p.z);
  float dx = p.x - fx, dy = p.y - fy, dz = p.z - fz;
  int ix = int(fx) & 255, iy = int(fy) & 255, iz = int(fz) & 255;
  // The corners' hashes perm[perm[perm[x] + y] + z], sharing their prefixes.
  const auto& P = kPerm.p;
  const int a = P[size_t(ix)] + iy, b = P[size_t(ix + 1)] + iy;
  const int aa = P[size_t(a)] + iz, ab = P[size_t(a + 1)] + iz, ba = P[size_t(b)] + iz, bb = P[size_t(b + 1)] + iz;
  float w000 = grad(P[size_t(aa)], dx, dy, dz), w100 = grad(P[size_t(ba)], dx - 1, dy, dz);
  float w010 = grad(P[size_t(ab)], dx, dy - 1, dz), w110 = grad(P[size_t(bb)], dx - 1, dy - 1, dz);
  float w001 = grad(P[size_t(aa + 1)], dx, dy, dz - 1), w101 = grad(P[size_t(ba + 1)], dx - 1, dy, dz - 1);
  float w011 = grad(P[size_t(ab + 1)], dx, dy - 1, dz - 1);
  float w111 = grad(P[size_t(bb + 1)], dx - 1, dy - 1, dz - 1);
  float wx = fade(dx), wy = fade(dy), wz = fade(dz);
  float y0 = lerp(wy, lerp(wx, w000, w100), lerp(wx, w010, w110));
  float y1 = lerp(wy, lerp(wx, w001, w101), lerp(wx, w011, w111));
  return lerp(wz, y0, y1);
}

namespace {

// How many octaves the footprint resolves, fractional: octave i has a
// period of about 1.99^-i, and is kept while that exceeds the footprint's
// length (pbrt-v4: n = -1 - log2(max |dp|^2) / 2, clamped to [0, octaves]).
float resolved_octaves(Vec3 dpdx, Vec3 dpdy, int octaves) {
  float len2 = max_num(glm::dot(dpdx, dpdx), glm::dot(dpdy, dpdy));
  float n = -1.f - 0.5f * std::log2(len2);  // +inf for a zero footprint
  return std::isnan(n) ? 0.f : glm::clamp(n, 0.f, float(octaves));
}

float smooth_step(float x, float a, float b) {
  float t = glm::clamp((x - a) / (b - a), 0.f, 1.f);
  return t * t * (3.f - 2.f * t);
}

}  // namespace

float fbm(Vec3 p, Vec3 dpdx, Vec3 dpdy, float omega, int octaves) {
  const float n = resolved_octaves(dpdx, dpdy, octaves);
  const int whole = int(std::floor(n));
  float sum = 0.f, lambda = 1.f, o = 1.f;
  for (int i = 0; i < whole; ++i) {
    sum += o * perlin_noise(lambda * p);
    lambda *= 1.99f;
    o *= omega;
  }
  // The partly resolved octave fades in.
  float fade_in = smooth_step(n - float(whole), 0.3f, 0.7f);
  return fade_in > 0.f ? sum + o * fade_in * perlin_noise(lambda * p) : sum;
}

float turbulence(Vec3 p, Vec3 dpdx, Vec3 dpdy, float omega, int octaves) {
  const float n = resolved_octaves(dpdx, dpdy, octaves);
  const int whole = int(std::floor(n));
  float sum = 0.f, lambda = 1.f, o = 1.f;
  for (int i = 0; i < whole; ++i) {
    sum += o * std::fabs(perlin_noise(lambda * p));
    lambda *= 1.99f;
    o *= omega;
  }
  // An unresolved octave of |noise| averages about 0.2: the partly resolved
  // one blends from that to its value, and each unresolved octave adds 0.2
  // at the partial octave's weight and on (pbrt-v4's sum, kept as it is).
  float fade_in = smooth_step(n - float(whole), 0.3f, 0.7f);
  float partial = fade_in > 0.f ? std::fabs(perlin_noise(lambda * p)) : 0.f;
  sum += o * ((1.f - fade_in) * 0.2f + fade_in * partial);
  for (int i = whole; i < octaves; ++i) {
    sum += o * 0.2f;
    o *= omega;
  }
  return sum;
}

float windy(Vec3 p, Vec3 dpdx, Vec3 dpdy) {
  float strength = fbm(0.1f * p, 0.1f * dpdx, 0.1f * dpdy, 0.5f, 3);
  float height = fbm(p, dpdx, dpdy, 0.5f, 6);
  return std::fabs(strength) * height;
}

RGB marble(Vec3 p, Vec3 dpdx, Vec3 dpdy, float omega, int octaves, float scale, float variation) {
  p *= scale;
  float t = 0.5f + 0.5f * std::sin(p.y + variation * fbm(p, scale * dpdx, scale * dpdy, omega, octaves));
  t = std::isfinite(t) ? glm::clamp(t, 0.f, 1.f) : 0.5f;
  // The control points of pbrt's marble colour spline (PBR, sec. 10.6.5),
  // cubic Bezier segments overlapping by three points.
  static const RGB c[] = {{.58f, .58f, .6f}, {.58f, .58f, .6f}, {.58f, .58f, .6f},
                          {.5f, .5f, .5f},   {.6f, .59f, .58f}, {.58f, .58f, .6f},
                          {.58f, .58f, .6f}, {.2f, .2f, .33f},  {.58f, .58f, .6f}};
  const int segments = 9 - 3;
  int first = std::min(int(std::floor(t * segments)), segments - 1);
  t = t * segments - float(first);
  const RGB* q = c + first;
  // de Casteljau
  RGB a = mix(q[0], q[1], t), b = mix(q[1], q[2], t), d = mix(q[2], q[3], t);
  RGB e = mix(a, b, t), f = mix(b, d, t);
  return 1.5f * mix(e, f, t);
}

}  // namespace lantern
