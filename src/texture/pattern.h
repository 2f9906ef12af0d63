// Procedural patterns that choose between two textures: the checkerboard
// (2D on the mapping's (s, t), or 3D on the texture-space point) and
// pbrt's polka dots. The checkerboard is filtered over the pixel footprint
// as pbrt-v4 filters it: a triangle filter of radius 1.5 footprints per
// axis, in closed form.
#pragma once

#include "texture/mapping.h"
#include "texture/noise.h"

namespace lantern {

// The square wave +1 on even unit cells, -1 on odd ones, averaged under a
// triangle filter of radius r centred on x. With S'' = square wave, the
// filtered value is (S(x + r) - 2 S(x) + S(x - r)) / r^2; S is the twice
// integrated wave, x/2 plus a periodic parabolic correction. In doubles,
// so no coordinate (huge, infinite or NaN) can overflow an integer.
inline double filtered_square_wave(double x, double r) {
  if (!std::isfinite(x)) return 1.0;
  if (!(r > 0.0) || std::floor(x - r) == std::floor(x + r))  // within one cell
    return std::fabs(std::fmod(std::floor(x), 2.0)) == 1.0 ? -1.0 : 1.0;
  auto S = [](double v) {
    double y = v / 2 - std::floor(v / 2) - 0.5;
    return v / 2 + y * (1 - 2 * std::fabs(y));
  };
  double w = (S(x + r) - 2 * S(x) + S(x - r)) / (r * r);
  return std::isfinite(w) ? glm::clamp(w, -1.0, 1.0) : 0.0;
}

// The weight of the second texture: 0 on even cells (tex1), 1 on odd ones,
// in between where the footprint covers both.
inline float checkerboard_2d(const TexCoord2D& c) {
  double rs = 1.5 * max_num(std::fabs(c.dst_dx.x), std::fabs(c.dst_dy.x));
  double rt = 1.5 * max_num(std::fabs(c.dst_dx.y), std::fabs(c.dst_dy.y));
  return float(0.5 - 0.5 * filtered_square_wave(c.st.x, rs) * filtered_square_wave(c.st.y, rt));
}
inline float checkerboard_3d(const TexCoord3D& c) {
  double w = 1.0;
  for (int k = 0; k < 3; ++k)
    w *= filtered_square_wave(c.p[k], 1.5 * max_num(std::fabs(c.dpdx[k]), std::fabs(c.dpdy[k])));
  return float(0.5 - 0.5 * w);
}

// Whether st falls in a dot: cells of unit size centred on integers hold a
// dot of radius 0.35 where the noise at the cell is positive, jittered
// within the cell by two more noise values (pbrt's DotsTexture).
inline bool inside_polka_dot(Vec2 st) {
  float s_cell = std::floor(st.x + 0.5f), t_cell = std::floor(st.y + 0.5f);
  if (!(perlin_noise(s_cell + 0.5f, t_cell + 0.5f) > 0.f)) return false;
  const float radius = 0.35f, max_shift = 0.5f - radius;
  float sc = s_cell + max_shift * perlin_noise(s_cell + 1.5f, t_cell + 2.8f);
  float tc = t_cell + max_shift * perlin_noise(s_cell + 4.5f, t_cell + 9.8f);
  Vec2 d = st - Vec2(sc, tc);
  return glm::dot(d, d) < radius * radius;
}

}  // namespace lantern
