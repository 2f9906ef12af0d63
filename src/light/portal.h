// pbrt-v4's "infinite" light with a "portal": an environment map that
// lights the scene only through a rectangular window (the one opening of
// a room), and is sampled only through it.
//
// Directions are parameterised by the portal's frame (x along p0->p3, y
// along p0->p1, z = x cross y): (u, v) = ((alpha + pi/2) / pi, (beta +
// pi/2) / pi) with alpha = atan2(w.x, w.z), beta = atan2(w.y, w.z). In these
// coordinates the directions from any point through the window form an
// axis-aligned rectangle, the image of the window's corners. The map is
// resampled into this parameterisation once; next-event estimation then
// samples the window's rectangle of it in proportion to radiance times
// solid angle (math/windowed_distribution.h). The solid angle per unit
// (u, v) is pi^2 (1 - w.x^2) (1 - w.y^2) / w.z.
//
// As in pbrt-v4, radiance arrives at a point only along directions through
// the window; light subpaths leave along any direction of the map (their
// first hit applies the window), from a disk as for other infinite lights.
#pragma once

#include <vector>

#include "math/frame.h"
#include "math/windowed_distribution.h"
#include "texture/image.h"

namespace lantern {

struct PortalMap {
  Vec3 corner[4];  // render space, pbrt's order
  Frame frame;
  TextureImage map;  // resampled into (u, v), times the light's scale; row 0 at v = 0
  WindowedDistribution2D distribution;
  float area = 0.f;
};

// Throws std::invalid_argument for corners that are not a rectangle.
PortalMap make_portal(const Vec3 corners[4], const TextureImage& equal_area_map, const glm::mat3& light_from_world,
                      const RGB& scale);

// Radiance arriving at p from direction w (unit, towards the light): zero
// unless w passes through the window from p.
RGB portal_Le(const PortalMap& m, const Vec3& p, const Vec3& w);
// Next-event estimation from p: a direction through the window.
bool sample_portal(const PortalMap& m, const Vec3& p, Vec2 u, Vec3* wi, float* pdf, RGB* L);
float portal_pdf(const PortalMap& m, const Vec3& p, const Vec3& w);
// Light subpaths: a direction towards the light from the whole map (its
// radiance without the window), and its density.
bool sample_portal_emission(const PortalMap& m, Vec2 u, Vec3* w_to_light, float* pdf, RGB* L);
float portal_emission_pdf(const PortalMap& m, const Vec3& w_to_light);
// Whether light travelling along -w_to_light reaches p through the window.
bool through_portal(const PortalMap& m, const Vec3& p, const Vec3& w_to_light);
// Flux through the window (for choosing among lights): area times the
// map's radiance integrated over the directions it parameterises.
float portal_power(const PortalMap& m);

}  // namespace lantern
