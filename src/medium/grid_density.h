// Media given on pbrt-v4's grids: nx x ny x nz samples at the centres of
// the cells that divide the box [p0, p1] of the medium's space, trilinear
// between neighbouring samples, and beyond the outer ones towards the zero
// of a sample outside the grid (half the outer sample at the box's faces),
// as pbrt-v4's SampledGrid looks them up.
//
// Along a ray, inside one cell of the lattice of samples, a sampled
// quantity is a cubic in the distance (a product of three linear
// interpolations). So its integral, the optical depth, is exact. So is the
// point where that integral reaches a given value (a monotone quartic,
// solved by Newton steps guarded by bisection). Distance sampling and
// transmittance therefore have no tracking noise, and the distance
// densities bidirectional MIS needs are known in closed form
// (docs/media.md). Cells whose eight samples are zero cost one test.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <memory>
#include <mutex>
#include <vector>

#include "color/color_space.h"
#include "color/spectrum_conversion.h"
#include "math/common.h"

namespace lantern {

// Where a lattice of samples at integer coordinates sits: lattice
// coordinates = m (render point, 1), and the box the medium fills, in
// lattice coordinates (cells outside it are empty).
struct LatticeFrame {
  double m[3][4] = {{1, 0, 0, 0}, {0, 1, 0, 0}, {0, 0, 1, 0}};
  double lo[3] = {0, 0, 0}, hi[3] = {1, 1, 1};
  // The frame whose m is a (lattice from the medium's space) after b (the
  // medium's space from render space).
  static LatticeFrame compose(const double a[3][4], const Mat4& b, const double lo[3], const double hi[3]);
};

struct GridLayout {
  int nx = 1, ny = 1, nz = 1;  // samples; x varies fastest, then y, then z (pbrt's order)
  Vec3 p0{0.f}, p1{1.f};       // the box, in the medium's space
  Mat4 medium_from_render{1.f};

  bool inside(int x, int y, int z) const { return x >= 0 && y >= 0 && z >= 0 && x < nx && y < ny && z < nz; }
  size_t offset(int x, int y, int z) const { return (size_t(z) * size_t(ny) + size_t(y)) * size_t(nx) + size_t(x); }
  // Lattice cell and weights of a point of render space; false outside the box.
  bool locate(const Vec3& p, int cell[3], double f[3]) const;
  // Samples at the cells' centres: the box is [-1/2, n - 1/2] in lattice coordinates.
  LatticeFrame frame() const;
};

namespace lattice {

// c[0] + c[1] s + c[2] s^2 + c[3] s^3, plus a constant part k.
struct Cubic {
  double c[4] = {0.0, 0.0, 0.0, 0.0};
  double k = 0.0;
  double value(double s) const { return k + c[0] + s * (c[1] + s * (c[2] + s * c[3])); }
  double integral(double s) const { return s * (k + c[0] + s * (c[1] / 2.0 + s * (c[2] / 3.0 + s * c[3] / 4.0))); }
};

// The trilinear interpolation of samples v along the ray inside one cell, as
// a cubic in the distance s from where it entered: f0 is the entry point's
// position in the cell ([0,1]^3), df its rate.
Cubic cell_cubic(const double f0[3], const double df[3], const float v[2][2][2]);

// The s in [0, S] where the (non-decreasing) integral of p reaches r, given
// that it reaches at least r by S.
double solve_integral(const Cubic& p, double S, double r);

// The integral of a density along a ray, cell by cell: with target >= 0 it
// stops where the integral reaches target (*t_hit, else infinity).
struct DepthSum {
  float target;
  float* t_hit;
  double sum = 0.0;
  bool reached = false;
  DepthSum(float target_, float* t_hit_) : target(target_), t_hit(t_hit_) { *t_hit = kInfinity; }
  // Reads the cell's eight samples with sample(x, y, z) (lattice indices)
  // and adds its part over [t, t_exit]; true once the target is reached.
  template <class Sample>
  bool add(const int c[3], double t, double t_exit, const double f0[3], const double dg[3], Sample&& sample) {
    float v[2][2][2];
    bool any = false;
    for (int a = 0; a < 2; ++a)
      for (int b = 0; b < 2; ++b)
        for (int e = 0; e < 2; ++e) any |= (v[a][b][e] = sample(c[0] + a, c[1] + b, c[2] + e)) != 0.f;
    return any && add(v, t, t_exit, f0, dg);  // cells with no sample cost this one test
  }
  bool add(const float v[2][2][2], double t, double t_exit, const double f0[3], const double dg[3]);
  float result() const { return reached ? target : float(sum); }
};

// Calls visit(cell, t_in, t_out, f0, dg) for the lattice cells that o + t d
// crosses inside the box, for t in [t0, t1], in order, until it returns
// true. f0: where the ray enters the cell, in the cell's coordinates; dg:
// their rate per unit t.
template <class Visit>
void walk(const LatticeFrame& frame, const Vec3& o, const Vec3& d, float t0, float t1, Visit&& visit) {
  double g0[3], dg[3], ta = t0, tb = t1;
  int first[3], last[3];  // the cells the box covers
  for (int k = 0; k < 3; ++k) {  // lattice coordinates, and the box they must stay in
    const double* m = frame.m[k];
    g0[k] = m[0] * o.x + m[1] * o.y + m[2] * o.z + m[3];
    dg[k] = m[0] * d.x + m[1] * d.y + m[2] * d.z;
    const double lo = frame.lo[k], hi = frame.hi[k];
    first[k] = int(std::floor(lo));
    last[k] = int(std::ceil(hi)) - 1;
    if (dg[k] == 0.0) {
      if (g0[k] < lo || g0[k] > hi) return;
      continue;
    }
    double ea = (lo - g0[k]) / dg[k], eb = (hi - g0[k]) / dg[k];
    if (ea > eb) std::swap(ea, eb);
    ta = std::max(ta, ea);
    tb = std::min(tb, eb);
  }
  if (!(ta < tb)) return;
  int cell[3], step[3];
  double t_next[3], t_delta[3];
  for (int k = 0; k < 3; ++k) {
    cell[k] = std::clamp(int(std::floor(g0[k] + ta * dg[k])), first[k], last[k]);
    step[k] = dg[k] > 0.0 ? 1 : -1;
    if (dg[k] == 0.0) {
      t_next[k] = t_delta[k] = kInfinity;
    } else {
      t_next[k] = ((dg[k] > 0.0 ? cell[k] + 1 : cell[k]) - g0[k]) / dg[k];
      t_delta[k] = 1.0 / std::fabs(dg[k]);
    }
  }
  for (double t = ta; t < tb;) {
    const int axis = t_next[0] < t_next[1] ? (t_next[0] < t_next[2] ? 0 : 2) : (t_next[1] < t_next[2] ? 1 : 2);
    const double t_exit = std::min(tb, t_next[axis]);
    if (t_exit > t) {
      const double f0[3] = {g0[0] + t * dg[0] - cell[0], g0[1] + t * dg[1] - cell[1], g0[2] + t * dg[2] - cell[2]};
      if (visit(cell, t, t_exit, f0, dg)) return;
    }
    if (t_exit >= tb) return;
    cell[axis] += step[axis];
    if (cell[axis] < first[axis] || cell[axis] > last[axis]) return;
    t_next[axis] += t_delta[axis];
    t = t_exit;
  }
}

}  // namespace lattice

// f(x, y, z) for the samples of layout g that weigh on some point of the
// region [u0, u1] of the box (unit coordinates), their trilinear
// neighbours included: the loose bounds that volume lights sample by.
template <class F>
void for_samples_over(const GridLayout& g, const Vec3& u0, const Vec3& u1, F&& f) {
  int lo[3], hi[3];
  const int n[3] = {g.nx, g.ny, g.nz};
  for (int k = 0; k < 3; ++k) {
    lo[k] = std::max(int(std::floor(u0[k] * float(n[k]) - 0.5f)), 0);
    hi[k] = std::min(int(std::floor(u1[k] * float(n[k]) - 0.5f)) + 1, n[k] - 1);
  }
  for (int z = lo[2]; z <= hi[2]; ++z)
    for (int y = lo[1]; y <= hi[1]; ++y)
      for (int x = lo[0]; x <= hi[0]; ++x) f(x, y, z);
}
// The largest f(x, y, z) over those samples (0 if none is positive).
template <class F>
float max_over(const GridLayout& g, const Vec3& u0, const Vec3& u1, F&& f) {
  float m = 0.f;
  for_samples_over(g, u0, u1, [&](int x, int y, int z) { m = std::max(m, f(x, y, z)); });
  return m;
}

// pbrt-v4's "uniformgrid" density.
struct DensityGrid : GridLayout {
  std::vector<float> values;
  // One bit per lattice cell the walk may cross ((nx + 1)(ny + 1)(nz + 1),
  // from -1 on each axis), set where any of its eight samples is nonzero,
  // so that an empty cell costs one bit; empty until find_occupied_cells
  // is called, when every cell reads its samples.
  std::vector<uint64_t> occupied;

  // Builds `occupied` from the values (after they change, again).
  void find_occupied_cells();
  // Sample (x, y, z); zero outside the grid.
  float sample(int x, int y, int z) const { return inside(x, y, z) ? values[offset(x, y, z)] : 0.f; }
  // The density at a point of render space.
  float density(const Vec3& p) const;
  // The integral of the density along o + t d (render space; d need not be
  // unit length, t is in its units) over [t0, t1]. With target >= 0, stops
  // where the integral reaches target: *t_hit is that t and target is
  // returned; otherwise *t_hit is infinity.
  float integrate(const Vec3& o, const Vec3& d, float t0, float t1, float target, float* t_hit) const;

 private:
  size_t cell_bit(const int c[3]) const {
    return (size_t(c[2] + 1) * size_t(ny + 1) + size_t(c[1] + 1)) * size_t(nx + 1) + size_t(c[0] + 1);
  }
  bool cell_samples(const int c[3], float v[2][2][2]) const;
};

// pbrt-v4's "rgbgrid": RGB absorption and scattering per sample (scaled);
// a grid not given is a constant 1 (times scale) inside the box.
struct RgbGrid : GridLayout {
  std::vector<RGB> sigma_a, sigma_s;  // empty when not given
  RGB constant_a{0.f}, constant_s{0.f};
  std::vector<RGB> Le;  // emission samples ("Le"); empty when not given
  // Samples given in another colour space (ColorSpace rec2020, dci-p3,
  // aces2065-1): their values in it, which sampled wavelengths read by
  // that space's own table, Le lit by that space's illuminant, as pbrt-v4
  // reads them (the vectors above hold them converted into sRGB, for the
  // RGB renderer). Null and empty for sRGB.
  const ColorSpace* space = nullptr;
  std::vector<RGB> own_a, own_s, own_Le;

  RGB sample_t(int x, int y, int z) const {
    if (!inside(x, y, z)) return RGB(0.f);
    const size_t i = offset(x, y, z);
    return (sigma_a.empty() ? RGB(0.f) : sigma_a[i]) + (sigma_s.empty() ? RGB(0.f) : sigma_s[i]);
  }
  // The coefficients at a point of render space.
  void at(const Vec3& p, RGB* a, RGB* s) const;
  // The Le samples, trilinear at a point of render space.
  RGB Le_at(const Vec3& p) const;
  // The optical depth per channel along o + t d over [t0, t1]; with
  // channel c and tau >= 0, stops where channel c's depth reaches tau
  // (*t_hit; otherwise infinity).
  RGB integrate(const Vec3& o, const Vec3& d, float t0, float t1, int c, float tau, float* t_hit) const;

  // With sampled wavelengths, as pbrt-v4's grid of RGB spectra: each
  // sample's colour is an unbounded spectrum (Le's an illuminant), and the
  // values at the wavelengths are interpolated, not the colours (the
  // conversion is not linear). A coefficient not given is a constant
  // spectrum. The spectra's shapes are found once, on the first look-up
  // with wavelengths, so an RGB render pays nothing for them.
  void at(const Vec3& p, const SampledWavelengths& l, Spectrum* a, Spectrum* s) const;
  Spectrum Le_at(const Vec3& p, const SampledWavelengths& l) const;
  // The optical depth at each wavelength, as integrate() (channel c of
  // the wavelengths).
  Spectrum integrate(const Vec3& o, const Vec3& d, float t0, float t1, int c, float tau, const SampledWavelengths& l,
                     float* t_hit) const;

 private:
  struct Spectra {
    std::vector<UnboundedSpectrum> a, s, Le;
    const ColorSpace* white = nullptr;  // Le's illuminant: the space's (null: D65)
    float white_scale = 1.f;            // to luminance 1
  };
  const Spectra& spectra() const;
  Spectrum sample_t(int x, int y, int z, const Spectra& sp, const SampledWavelengths& l) const;
  // Found once, on first use; a copy of the grid (made while the scene is
  // built, before any look-up) shares them.
  struct SpectraOnce {
    std::once_flag once;
    Spectra spectra;
  };
  std::shared_ptr<SpectraOnce> spectra_ = std::make_shared<SpectraOnce>();
};

}  // namespace lantern
