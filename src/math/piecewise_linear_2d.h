// A density on the unit square that interpolates a grid of values
// bilinearly, optionally given at several values of up to three parameters
// (interpolated linearly between them). Sampling inverts it as a marginal
// over rows followed by a conditional over the row's columns, each a
// piecewise-linear density inverted in closed form (Dupuy & Jakob 2018,
// "An Adaptive Parameterization for Efficient Material Acquisition and
// Rendering", sec. 5). invert() is sample()'s exact inverse: tabulated BSDF
// files store their values over the unit square that this warp makes.
#pragma once

#include <cstdint>
#include <vector>

#include "math/common.h"

namespace lantern {

class PiecewiseLinear2D {
 public:
  static constexpr int kMaxParams = 3;
  struct Sample {
    Vec2 p{0.f};
    float pdf = 0.f;
  };

  PiecewiseLinear2D() = default;
  // `values` holds one grid per combination of parameter values, the last
  // parameter varying fastest; a grid is ny rows of nx values (x fastest),
  // the corners of (nx - 1) x (ny - 1) cells covering the unit square.
  // `params[i]` lists parameter i's values, ascending. With `warp`, each
  // grid is normalised to a density with the tables sample() and invert()
  // need (a grid of zeros becomes uniform); without, evaluate() returns the
  // values as given.
  PiecewiseLinear2D(const float* values, int nx, int ny, std::vector<std::vector<float>> params, bool warp);

  // Maps uniform u to a point distributed as the density at these
  // parameter values (one number per parameter), and its density.
  Sample sample(Vec2 u, const float* param) const;
  // The u that sample() maps to p, and the density at p.
  Sample invert(Vec2 p, const float* param) const;
  // The interpolated value (with `warp`: the density) at p.
  float evaluate(Vec2 p, const float* param) const;

  size_t memory_bytes() const;

 private:
  // The grids a parameter point interpolates, with their weights.
  struct Blend {
    uint32_t slice[1 << kMaxParams];
    float weight[1 << kMaxParams];
    int count = 0;
  };
  Blend blend(const float* param) const;
  // The cell holding p, p's place in it (s, t) and the density along the
  // row through p at the cell's two columns.
  struct Cell {
    int col, row;
    float s, t, c0, c1;
  };
  Cell cell_at(Vec2 p, const Blend& b) const;
  float lookup(const std::vector<float>& table, size_t per_slice, const Blend& b, size_t i) const;

  int nx_ = 0, ny_ = 0;
  float density_scale_ = 1.f;  // from normalised cell units to a density over the unit square
  std::vector<std::vector<float>> params_;
  std::vector<uint32_t> strides_;
  std::vector<float> data_;
  std::vector<float> marginal_;     // per grid: the integral over rows 0..y, in cell units
  std::vector<float> conditional_;  // per grid and row: the integral over columns 0..x
};

}  // namespace lantern
