// Catmull-Rom splines over non-uniform nodes, with derivatives from finite
// differences of the neighbouring nodes (one-sided at the ends), as the
// Fourier BSDF tables of Jakob et al. 2014 ("A Comprehensive Framework for
// Rendering Layered Materials") interpolate their zenith cosines: weights
// for four nodes, the spline's exact integral, and sampling proportional to
// a spline whose node values are themselves interpolated along a second
// axis (Pharr, Jakob & Humphreys, Physically Based Rendering, 3rd ed.,
// sec. 8.6.1-8.6.2).
#pragma once

#include <vector>

namespace lantern {

// The spline at x is sum over i of weight[i] * value[offset + i]; weights
// of nodes outside the table are 0 (offset may be -1 then).
struct SplineWeights {
  int offset = 0;
  float weight[4] = {0.f, 0.f, 0.f, 0.f};
};
// False when x lies outside [nodes.front(), nodes.back()].
bool catmull_rom_weights(const std::vector<float>& nodes, float x, SplineWeights* out);

// The integral of the spline through (nodes, values), and in cdf (resized
// to nodes.size()) its running integral up to each node.
float integrate_catmull_rom(const std::vector<float>& nodes, const float* values, std::vector<float>* cdf);

// A table over (nodes1 x nodes2): values and their running integrals
// along nodes2 (cdf), row i at [i * nodes2.size()]. Draws x along nodes2
// with density proportional to the spline through the rows interpolated at
// alpha along nodes1.
struct SplineSample {
  float x = 0.f;
  float value = 0.f;  // the interpolated spline at x
  float pdf = 0.f;    // value / its integral
};
SplineSample sample_catmull_rom_2d(const std::vector<float>& nodes1, const std::vector<float>& nodes2,
                                   const float* values, const float* cdf, float alpha, float u);

}  // namespace lantern
