// A piecewise-constant function on [0,1]^2 (one value per cell of an
// nu x nv grid) that can be sampled within any axis-aligned window of it,
// in proportion to its values there: a portal light draws only the
// directions its window lets through from the point being lit. Built on a
// summed-area table, whose integral over [0,u] x [0,v] is bilinear within
// each cell, so the window's marginal and conditional CDFs are piecewise
// linear and are inverted exactly, by a binary search over cell edges.
#pragma once

#include <vector>

#include "math/common.h"

namespace lantern {

class WindowedDistribution2D {
 public:
  WindowedDistribution2D() = default;
  // f: nv rows of nu non-negative values, row 0 at v = 0.
  WindowedDistribution2D(const std::vector<float>& f, int nu, int nv);

  bool empty() const { return f_.empty(); }
  // The integral of f over the window [lo, hi].
  double integral(Vec2 lo, Vec2 hi) const;
  // A point of the window with density f / integral (per unit area of
  // [0,1]^2); false where the window holds nothing.
  bool sample(Vec2 u, Vec2 lo, Vec2 hi, Vec2* p, float* pdf) const;
  float pdf(Vec2 p, Vec2 lo, Vec2 hi) const;

 private:
  double sat(double u, double v) const;  // integral over [0,u] x [0,v]
  float value(Vec2 p) const;
  int nu_ = 0, nv_ = 0;
  std::vector<float> f_;
  std::vector<double> sat_;  // (nv + 1) x (nu + 1) corner values
};

}  // namespace lantern
