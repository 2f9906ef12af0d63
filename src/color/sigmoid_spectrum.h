// Smooth spectra from three numbers (Jakob & Hanika 2019, "A Low-Dimensional
// Function Space for Efficient Spectral Upsampling"): a quadratic in
// wavelength passed through a sigmoid, s(l) = S(c0 t^2 + c1 t + c2) with
// S(x) = 1/2 + x / (2 sqrt(1 + x^2)) (their eq. 3), which stays within
// (0, 1) as a reflectance must. Here t is the wavelength mapped onto
// [0, 1] over 360-830 nm, the range the coefficients are fitted on.
#pragma once

#include <cmath>

#include "math/max_num.h"

namespace lantern {

constexpr float kLambdaMin = 360.f, kLambdaMax = 830.f;  // the visible range sampled (nm)

inline float sigmoid(float x) {
  if (std::isinf(x)) return x > 0.f ? 1.f : 0.f;  // a constant 0 or 1
  return 0.5f + x / (2.f * std::sqrt(1.f + x * x));
}

struct SigmoidPolynomial {
  float c0 = 0.f, c1 = 0.f, c2 = 0.f;

  float operator()(float nm) const {
    const float t = (nm - kLambdaMin) * (1.f / (kLambdaMax - kLambdaMin));
    return sigmoid((c0 * t + c1) * t + c2);
  }
  // The largest value over the range: at an end, or at the quadratic's
  // extremum when it lies inside.
  float max_value() const {
    float m = max_num((*this)(kLambdaMin), (*this)(kLambdaMax));
    if (c0 != 0.f) {
      const float t = -c1 / (2.f * c0);
      if (t > 0.f && t < 1.f) m = max_num(m, sigmoid((c0 * t + c1) * t + c2));
    }
    return m;
  }
  // The constant spectrum v in [0, 1].
  static SigmoidPolynomial constant(float v) {
    if (!(v > 0.f)) return {0.f, 0.f, -INFINITY};
    if (!(v < 1.f)) return {0.f, 0.f, INFINITY};
    return {0.f, 0.f, (v - 0.5f) / std::sqrt(v * (1.f - v))};  // the sigmoid's inverse
  }
};

}  // namespace lantern
