// Even Fourier series in an azimuth difference, f(phi) = sum a_k cos(k phi)
// for k < m: evaluation by the cosines' recurrence
// cos((k+1) phi) = 2 cos(phi) cos(k phi) - cos((k-1) phi), and sampling
// proportional to f over [0, 2 pi) by inverting its integral
// a_0 phi + sum a_k sin(k phi) / k on [0, pi] with Newton steps kept in a
// bisection bracket (Jakob et al. 2014; Physically Based Rendering, 3rd
// ed., sec. 8.6.3).
#pragma once

namespace lantern {

float fourier(const float* a, int m, double cos_phi);

struct FourierSample {
  float phi = 0.f;
  float value = 0.f;  // f(phi)
  float pdf = 0.f;    // f(phi) / (2 pi a_0), per radian
};
FourierSample sample_fourier(const float* a, int m, float u);

}  // namespace lantern
