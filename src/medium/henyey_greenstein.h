// The Henyey-Greenstein phase function (Henyey & Greenstein 1941), with
// pbrt's convention: wo and wi both point away from the scattering point, so
// forward scattering (g > 0) favours wi = -wo.
#pragma once

#include "math/frame.h"

namespace lantern {

struct HenyeyGreenstein {
  float g = 0.f;  // mean cosine, in (-1, 1)

  // Density over solid angle of the angle between -wo and wi.
  float p(const Vec3& wo, const Vec3& wi) const { return density(-glm::dot(wo, wi)); }
  float pdf(const Vec3& wo, const Vec3& wi) const { return p(wo, wi); }

  // Samples wi exactly in proportion to p; returns it with its density.
  Vec3 sample(const Vec3& wo, Vec2 u, float* pdf) const {
    // Inverse CDF of the cosine to the forward direction -wo.
    float cos_t;
    if (std::fabs(g) < 1e-3f) {
      cos_t = 1.f - 2.f * u.x;
    } else {
      float q = (1.f - g * g) / (1.f - g + 2.f * g * u.x);
      cos_t = glm::clamp((1.f + g * g - q * q) / (2.f * g), -1.f, 1.f);
    }
    float sin_t = safe_sqrt(1.f - cos_t * cos_t), phi = 2.f * kPi * u.y;
    Frame f = Frame::from_z(-wo);
    Vec3 wi = f.from_local(Vec3(sin_t * std::cos(phi), sin_t * std::sin(phi), cos_t));
    *pdf = density(cos_t);
    return wi;
  }

 private:
  // cos_t: cosine between the forward direction and the scattered one.
  float density(float cos_t) const {
    float d = 1.f + g * g - 2.f * g * cos_t;
    return kInv4Pi * (1.f - g * g) / (d * safe_sqrt(d));
  }
};

}  // namespace lantern
