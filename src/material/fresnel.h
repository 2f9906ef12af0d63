// Fresnel reflectance for dielectric and conducting interfaces.
#pragma once

#include <complex>

#include "math/common.h"

namespace lantern {

// Unpolarised reflectance of a dielectric interface; eta = eta_t / eta_i for
// a direction on the outside (cos_i > 0); cos_i < 0 means from inside.
inline float fr_dielectric(float cos_i, float eta) {
  cos_i = glm::clamp(cos_i, -1.f, 1.f);
  if (cos_i < 0.f) {
    eta = 1.f / eta;
    cos_i = -cos_i;
  }
  float sin2_i = 1.f - cos_i * cos_i;
  float sin2_t = sin2_i / (eta * eta);
  if (sin2_t >= 1.f) return 1.f;
  float cos_t = safe_sqrt(1.f - sin2_t);
  float r_parl = (eta * cos_i - cos_t) / (eta * cos_i + cos_t);
  float r_perp = (cos_i - eta * cos_t) / (cos_i + eta * cos_t);
  return 0.5f * (r_parl * r_parl + r_perp * r_perp);
}

// Reflectance of a conductor with complex index eta + i k.
inline float fr_complex(float cos_i, float eta, float k) {
  using C = std::complex<float>;
  cos_i = glm::clamp(cos_i, 0.f, 1.f);
  C e(eta, k);
  float sin2_i = 1.f - cos_i * cos_i;
  C sin2_t = sin2_i / (e * e);
  C cos_t = std::sqrt(C(1.f) - sin2_t);
  C r_parl = (e * cos_i - cos_t) / (e * cos_i + cos_t);
  C r_perp = (cos_i - e * cos_t) / (cos_i + e * cos_t);
  return 0.5f * (std::norm(r_parl) + std::norm(r_perp));
}

inline Spectrum fr_complex(float cos_i, const Spectrum& eta, const Spectrum& k) {
  Spectrum r;
  for (int c = 0; c < Spectrum::kSize; ++c) r[c] = fr_complex(cos_i, eta[c], k[c]);
  return r;
}

}  // namespace lantern
