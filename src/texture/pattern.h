// Procedural patterns that choose between two textures: the checkerboard
// (2D on the mapping's (s, t), or 3D on the texture-space point) and
// pbrt's polka dots. Lantern has no ray differentials yet, so the
// checkerboard is point-sampled; pbrt-v4 box-filters it over the pixel
// footprint, which antialiases edges and keeps the mean.
#pragma once

#include "texture/noise.h"

namespace lantern {

// The weight of the second texture: 0 on even cells (tex1), 1 on odd ones.
// In doubles, so that no coordinate (huge, infinite or NaN: tex1) can
// overflow an integer.
inline float checker_parity(double cells) { return std::fabs(std::fmod(cells, 2.0)) == 1.0 ? 1.f : 0.f; }
inline float checkerboard_2d(Vec2 st) { return checker_parity(std::floor(double(st.x)) + std::floor(double(st.y))); }
inline float checkerboard_3d(Vec3 p) {
  return checker_parity(std::floor(double(p.x)) + std::floor(double(p.y)) + std::floor(double(p.z)));
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
