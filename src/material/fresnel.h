// Fresnel reflectance for dielectric and conducting interfaces.
#pragma once

#include <cmath>
#include <limits>

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

// The principal square root a + i b of x + i y: a >= 0, and b has y's sign
// (signed zeros included), the branch csqrtf takes (C99 Annex G). With r =
// |x + i y|, a^2 = (r + x) / 2 and b^2 = (r - x) / 2; the larger of the
// two comes from r + |x|, which cannot cancel, and the smaller from y = 2ab
// (the idea of W. Kahan's "Branch cuts for complex elementary functions",
// 1987, without its scaling: x^2 + y^2 must neither overflow nor underflow,
// which fr_complex's range of indices ensures).
inline void complex_sqrt(float x, float y, float* re, float* im) {
  const float r = std::sqrt(x * x + y * y);
  if (r == 0.f) {
    *re = 0.f;
    *im = y;
    return;
  }
  const float larger = std::sqrt(0.5f * (r + std::fabs(x)));
  const float smaller = std::fabs(y) / (2.f * larger);
  *re = x >= 0.f ? larger : smaller;
  *im = std::copysign(x >= 0.f ? smaller : larger, y);
}

// Reflectance of a conductor with complex index e = eta + i k, from the
// Fresnel equations with a complex index: sin^2 t = sin^2 i / e^2, cos t =
// sqrt(1 - sin^2 t), r_parallel = (e cos i - cos t) / (e cos i + cos t)
// and r_perpendicular = (cos i - e cos t) / (cos i + e cos t). Only |r|^2
// is needed, and |a / b|^2 = |a|^2 / |b|^2: so no complex division, which
// GCC leaves to a library call (libgcc's __divsc3, with its overflow and
// NaN cases), and the square root written out rather than csqrtf.
inline float fr_complex(float cos_i, float eta, float k) {
  cos_i = glm::clamp(cos_i, 0.f, 1.f);
  const float sin2_i = 1.f - cos_i * cos_i;
  // sin^2 t = sin^2 i conj(e^2) / |e^2|^2, with e^2 = (eta^2 - k^2) + i 2 eta k.
  const float e2_re = eta * eta - k * k, e2_im = 2.f * eta * k;
  const float e2_norm = e2_re * e2_re + e2_im * e2_im;
  // Outside |e| in about [3.3e-10, 4.3e9] the squares below would overflow
  // (inf / inf) or s would (inf * 0); there 1 - R is below float's
  // resolution but for the last 1e-8 of cos i.
  if (!(e2_norm >= std::numeric_limits<float>::min() && e2_norm <= std::numeric_limits<float>::max())) return 1.f;
  const float s = sin2_i / e2_norm;
  float ct_re, ct_im;
  complex_sqrt(1.f - s * e2_re, s * e2_im, &ct_re, &ct_im);
  const float ec_re = eta * cos_i, ec_im = k * cos_i;                              // e cos i
  const float ect_re = eta * ct_re - k * ct_im, ect_im = eta * ct_im + k * ct_re;  // e cos t
  // A ratio of squared moduli. The denominator vanishes only at grazing
  // incidence on an index of exactly 1 (or -1), where the formula is 0 / 0:
  // 1 there, the limit of indices near 1 at grazing incidence (the old
  // complex division: NaN).
  auto ratio = [](float a_re, float a_im, float b_re, float b_im) {
    const float b = b_re * b_re + b_im * b_im;
    return b == 0.f ? 1.f : (a_re * a_re + a_im * a_im) / b;
  };
  const float r_parl = ratio(ec_re - ct_re, ec_im - ct_im, ec_re + ct_re, ec_im + ct_im);
  const float r_perp = ratio(cos_i - ect_re, -ect_im, cos_i + ect_re, ect_im);
  // (Rounding leaves it up to 2.4e-7 above 1 for 40 in a million indices.)
  const float r = 0.5f * (r_parl + r_perp);
  return r > 1.f ? 1.f : r;
}

inline Spectrum fr_complex(float cos_i, const Spectrum& eta, const Spectrum& k) {
  Spectrum r;
  for (int c = 0; c < Spectrum::kSize; ++c) r[c] = fr_complex(cos_i, eta[c], k[c]);
  return r;
}

}  // namespace lantern
