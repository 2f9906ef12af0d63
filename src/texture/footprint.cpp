#include "texture/footprint.h"

namespace lantern {
namespace {

// The rotation taking unit vector a to unit vector b about their common
// normal (Rodrigues), applied to x; a half turn when they are opposite.
Vec3 rotate_from_to(const Vec3& a, const Vec3& b, const Vec3& x) {
  float c = glm::dot(a, b);
  if (c > -0.9999f) {
    Vec3 v = glm::cross(a, b);
    return x * c + glm::cross(v, x) + v * (glm::dot(v, x) / (1.f + c));
  }
  Frame f = Frame::from_z(a);
  return 2.f * glm::dot(f.s, x) * f.s - x;
}

void keep_shorter(Vec3* best, const Vec3& v) {
  if (glm::dot(v, v) < glm::dot(*best, *best)) *best = v;
}

}  // namespace

FootprintModel::FootprintModel(const Camera& camera, int samples_per_pixel) : enabled_(true) {
  origin_ = camera.position();
  forward_ = camera.forward();
  // The smallest differentials over a grid of film positions, from rays
  // through the lens centre.
  const Vec3 far(1e30f);
  min_pos_dx_ = min_pos_dy_ = min_dir_dx_ = min_dir_dy_ = far;
  const int steps = 32;
  const Vec2 centre(0.5f);
  for (int j = 0; j <= steps; ++j)
    for (int i = 0; i <= steps; ++i) {
      Vec2 p(float(i) / steps * float(camera.width() - 1), float(j) / steps * float(camera.height() - 1));
      CameraRay r = camera.generate_ray(p, centre);
      CameraRay rx = camera.generate_ray(p + Vec2(1.f, 0.f), centre);
      CameraRay ry = camera.generate_ray(p + Vec2(0.f, 1.f), centre);
      keep_shorter(&min_pos_dx_, rx.o - r.o);
      keep_shorter(&min_pos_dy_, ry.o - r.o);
      keep_shorter(&min_dir_dx_, rx.d - r.d);
      keep_shorter(&min_dir_dy_, ry.d - r.d);
    }
  spp_scale_ = max_num(0.125f, 1.f / std::sqrt(float(std::max(1, samples_per_pixel))));
}

void FootprintModel::dp_dxy(const Vec3& p, const Vec3& n, Vec3* dpdx, Vec3* dpdy) const {
  *dpdx = *dpdy = Vec3(0.f);
  if (!enabled_) return;
  Vec3 w = p - origin_;
  float dist = glm::length(w);
  if (!(dist > 0.f) || !std::isfinite(dist)) return;
  w /= dist;
  auto offset = [&](const Vec3& pos_diff, const Vec3& dir_diff) {
    Vec3 o = origin_ + rotate_from_to(forward_, w, pos_diff);
    Vec3 d = w + rotate_from_to(forward_, w, dir_diff);
    float t = glm::dot(n, p - o) / glm::dot(n, d);
    Vec3 q = spp_scale_ * (o + t * d - p);
    return is_finite(q) ? q : Vec3(0.f);
  };
  *dpdx = offset(min_pos_dx_, min_dir_dx_);
  *dpdy = offset(min_pos_dy_, min_dir_dy_);
}

Footprint FootprintModel::at(const Vec3& p, const Vec3& n, const Vec3& dpdu, const Vec3& dpdv) const {
  Footprint f;
  dp_dxy(p, n, &f.dpdx, &f.dpdy);
  // The (du, dv) whose dpdu du + dpdv dv comes closest to dp/dx (and dp/dy):
  // the 2x2 normal equations.
  float a00 = glm::dot(dpdu, dpdu), a01 = glm::dot(dpdu, dpdv), a11 = glm::dot(dpdv, dpdv);
  float det = a00 * a11 - a01 * a01;
  float inv = det != 0.f && std::isfinite(1.f / det) ? 1.f / det : 0.f;
  auto solve = [&](const Vec3& dp) {
    float bu = glm::dot(dpdu, dp), bv = glm::dot(dpdv, dp);
    Vec2 r((a11 * bu - a01 * bv) * inv, (a00 * bv - a01 * bu) * inv);
    for (int k = 0; k < 2; ++k) r[k] = std::isfinite(r[k]) ? glm::clamp(r[k], -1e8f, 1e8f) : 0.f;
    return r;
  };
  f.duvdx = solve(f.dpdx);
  f.duvdy = solve(f.dpdy);
  return f;
}

}  // namespace lantern
