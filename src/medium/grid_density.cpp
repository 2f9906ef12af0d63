#include "medium/grid_density.h"

#include "color/rgb_spectrum_fit.h"

#include <array>

namespace lantern {

bool GridLayout::locate(const Vec3& p, int cell[3], double f[3]) const {
  const Vec3 pm = Vec3(medium_from_render * Vec4(p, 1.f));
  const Vec3 u = (pm - p0) / (p1 - p0);
  if (u.x < 0.f || u.y < 0.f || u.z < 0.f || u.x > 1.f || u.y > 1.f || u.z > 1.f) return false;
  const double g[3] = {double(u.x) * nx - 0.5, double(u.y) * ny - 0.5, double(u.z) * nz - 0.5};
  for (int k = 0; k < 3; ++k) {
    cell[k] = int(std::floor(g[k]));
    f[k] = g[k] - cell[k];
  }
  return true;
}

LatticeFrame LatticeFrame::compose(const double a[3][4], const Mat4& b, const double lo[3], const double hi[3]) {
  LatticeFrame f;
  for (int k = 0; k < 3; ++k) {
    for (int j = 0; j < 4; ++j) {  // glm: b[column][row]
      double v = j == 3 ? a[k][3] : 0.0;
      for (int i = 0; i < 3; ++i) v += a[k][i] * double(b[j][i]);
      f.m[k][j] = v;
    }
    f.lo[k] = lo[k], f.hi[k] = hi[k];
  }
  return f;
}

LatticeFrame GridLayout::frame() const {
  const int n[3] = {nx, ny, nz};
  double a[3][4] = {}, lo[3], hi[3];
  for (int k = 0; k < 3; ++k) {  // (p - p0) / (p1 - p0) n - 1/2
    const double s = n[k] / (double(p1[k]) - double(p0[k]));
    a[k][k] = s;
    a[k][3] = -double(p0[k]) * s - 0.5;
    lo[k] = -0.5, hi[k] = n[k] - 0.5;
  }
  return LatticeFrame::compose(a, medium_from_render, lo, hi);
}

namespace lattice {

Cubic cell_cubic(const double f0[3], const double df[3], const float v[2][2][2]) {
  // Each weight is linear in s: (a, b) for a + b s.
  const double x[2][2] = {{1.0 - f0[0], -df[0]}, {f0[0], df[0]}};
  const double y[2][2] = {{1.0 - f0[1], -df[1]}, {f0[1], df[1]}};
  const double z[2][2] = {{1.0 - f0[2], -df[2]}, {f0[2], df[2]}};
  Cubic out;
  for (int k = 0; k < 2; ++k) {
    double quad[3] = {0.0, 0.0, 0.0};
    for (int j = 0; j < 2; ++j) {
      const double la = v[0][j][k] * x[0][0] + v[1][j][k] * x[1][0], lb = v[0][j][k] * x[0][1] + v[1][j][k] * x[1][1];
      quad[0] += la * y[j][0];
      quad[1] += la * y[j][1] + lb * y[j][0];
      quad[2] += lb * y[j][1];
    }
    out.c[0] += quad[0] * z[k][0];
    out.c[1] += quad[0] * z[k][1] + quad[1] * z[k][0];
    out.c[2] += quad[1] * z[k][1] + quad[2] * z[k][0];
    out.c[3] += quad[2] * z[k][1];
  }
  return out;
}

bool DepthSum::add(const float v[2][2][2], double t, double t_exit, const double f0[3], const double dg[3]) {
  const Cubic p = cell_cubic(f0, dg, v);
  const double S = t_exit - t, I = std::max(0.0, p.integral(S));
  if (target >= 0.f && sum + I >= target) {
    *t_hit = float(t + solve_integral(p, S, double(target) - sum));
    return reached = true;
  }
  sum += I;
  return false;
}

double solve_integral(const Cubic& p, double S, double r) {
  double lo = 0.0, hi = S;
  const double total = p.integral(S);
  double s = total > 0.0 ? S * r / total : 0.5 * S;
  for (int it = 0; it < 60; ++it) {
    const double f = p.integral(s) - r;
    if (f > 0.0) hi = s;
    else lo = s;
    if (std::fabs(f) <= 1e-12 * std::max(r, 1e-300) || hi - lo <= 1e-12 * S) break;
    const double rho = p.value(s);
    double next = rho > 0.0 ? s - f / rho : 0.5 * (lo + hi);
    if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
    s = next;
  }
  return std::clamp(s, 0.0, S);
}

}  // namespace lattice

namespace {

template <class Sample>
auto trilinear(const int cell[3], const double f[3], Sample&& sample) {
  decltype(sample(0, 0, 0)) v{};
  for (int a = 0; a < 2; ++a)
    for (int b = 0; b < 2; ++b)
      for (int c = 0; c < 2; ++c)
        v += sample(cell[0] + a, cell[1] + b, cell[2] + c) *
             float((a ? f[0] : 1.0 - f[0]) * (b ? f[1] : 1.0 - f[1]) * (c ? f[2] : 1.0 - f[2]));
  return v;
}

}  // namespace

float DensityGrid::density(const Vec3& p) const {
  int cell[3];
  double f[3];
  if (!locate(p, cell, f)) return 0.f;
  return trilinear(cell, f, [&](int x, int y, int z) { return sample(x, y, z); });
}

// The eight samples of lattice cell c (v[x][y][z] offsets); false if all
// are zero. A cell inside the grid reads them at fixed strides from its
// first: only the cells at the box's faces, whose outer samples are zero,
// test each sample's indices.
bool DensityGrid::cell_samples(const int c[3], float v[2][2][2]) const {
  if (!occupied.empty()) {
    const size_t bit = cell_bit(c);
    if (!((occupied[bit >> 6] >> (bit & 63)) & 1)) return false;
  }
  if (c[0] >= 0 && c[1] >= 0 && c[2] >= 0 && c[0] + 1 < nx && c[1] + 1 < ny && c[2] + 1 < nz) {
    const size_t sy = size_t(nx), sz = size_t(nx) * size_t(ny);
    const float* p = values.data() + offset(c[0], c[1], c[2]);
    for (int e = 0; e < 2; ++e, p += sz) {
      v[0][0][e] = p[0], v[1][0][e] = p[1];
      v[0][1][e] = p[sy], v[1][1][e] = p[sy + 1];
    }
  } else {
    for (int a = 0; a < 2; ++a)
      for (int b = 0; b < 2; ++b)
        for (int e = 0; e < 2; ++e) v[a][b][e] = sample(c[0] + a, c[1] + b, c[2] + e);
  }
  bool any = false;
  for (int a = 0; a < 8; ++a) any |= v[a >> 2][(a >> 1) & 1][a & 1] != 0.f;
  return any;
}

void DensityGrid::find_occupied_cells() {
  occupied.assign(((size_t(nx) + 1) * (size_t(ny) + 1) * (size_t(nz) + 1) + 63) / 64, 0);
  for (int z = 0; z < nz; ++z)
    for (int y = 0; y < ny; ++y)
      for (int x = 0; x < nx; ++x) {
        if (values[offset(x, y, z)] == 0.f) continue;
        for (int e = 0; e < 2; ++e)  // the eight cells this sample is a corner of
          for (int b = 0; b < 2; ++b)
            for (int a = 0; a < 2; ++a) {
              const int c[3] = {x - a, y - b, z - e};
              const size_t bit = cell_bit(c);
              occupied[bit >> 6] |= uint64_t(1) << (bit & 63);
            }
      }
}

float DensityGrid::integrate(const Vec3& o, const Vec3& d, float t0, float t1, float target, float* t_hit) const {
  lattice::DepthSum depth(target, t_hit);
  lattice::walk(frame(), o, d, t0, t1, [&](const int c[3], double t, double t_exit, const double f0[3], const double dg[3]) {
    float v[2][2][2];
    return cell_samples(c, v) && depth.add(v, t, t_exit, f0, dg);  // (an empty cell costs its bit)
  });
  return depth.result();
}

void RgbGrid::at(const Vec3& p, RGB* a, RGB* s) const {
  int cell[3];
  double f[3];
  *a = *s = RGB(0.f);
  if (!locate(p, cell, f)) return;
  auto pick = [&](const std::vector<RGB>& grid) {
    return [&](int x, int y, int z) { return inside(x, y, z) ? grid[offset(x, y, z)] : RGB(0.f); };
  };
  *a = constant_a + (sigma_a.empty() ? RGB(0.f) : trilinear(cell, f, pick(sigma_a)));
  *s = constant_s + (sigma_s.empty() ? RGB(0.f) : trilinear(cell, f, pick(sigma_s)));
}

RGB RgbGrid::Le_at(const Vec3& p) const {
  int cell[3];
  double f[3];
  if (Le.empty() || !locate(p, cell, f)) return RGB(0.f);
  return trilinear(cell, f, [&](int x, int y, int z) { return inside(x, y, z) ? Le[offset(x, y, z)] : RGB(0.f); });
}

namespace {

// The optical depth of N channels along o + t d over [t0, t1], each cell's
// samples given by corner(x, y, z) (N values) plus a constant part; with
// channel c and tau >= 0, stops where channel c's depth reaches tau.
template <int N, class Corner>
std::array<double, N> integrate_channels(const LatticeFrame& frame, const Vec3& o, const Vec3& d, float t0, float t1,
                                         int c, float tau, float* t_hit, Corner&& corner, const float constant[N]) {
  *t_hit = kInfinity;
  std::array<double, N> sum{};
  lattice::walk(frame, o, d, t0, t1, [&](const int cell[3], double t, double t_exit, const double f0[3], const double dg[3]) {
    using V = decltype(corner(0, 0, 0));
    V v[2][2][2];
    for (int a = 0; a < 2; ++a)
      for (int b = 0; b < 2; ++b)
        for (int e = 0; e < 2; ++e) v[a][b][e] = corner(cell[0] + a, cell[1] + b, cell[2] + e);
    lattice::Cubic p[N];
    for (int k = 0; k < N; ++k) {
      float vk[2][2][2];
      for (int a = 0; a < 8; ++a) vk[a >> 2][(a >> 1) & 1][a & 1] = v[a >> 2][(a >> 1) & 1][a & 1][k];
      p[k] = lattice::cell_cubic(f0, dg, vk);
      p[k].k = constant[k];
    }
    const double S = t_exit - t;
    if (tau >= 0.f && sum[size_t(c)] + std::max(0.0, p[c].integral(S)) >= tau) {
      const double s = lattice::solve_integral(p[c], S, double(tau) - sum[size_t(c)]);
      for (int k = 0; k < N; ++k) sum[size_t(k)] += k == c ? double(tau) - sum[size_t(k)] : std::max(0.0, p[k].integral(s));
      *t_hit = float(t + s);
      return true;
    }
    for (int k = 0; k < N; ++k) sum[size_t(k)] += std::max(0.0, p[k].integral(S));
    return false;
  });
  return sum;
}

}  // namespace

RGB RgbGrid::integrate(const Vec3& o, const Vec3& d, float t0, float t1, int c, float tau, float* t_hit) const {
  const RGB k = constant_a + constant_s;
  const float constant[3] = {k[0], k[1], k[2]};
  const std::array<double, 3> sum = integrate_channels<3>(
      frame(), o, d, t0, t1, c, tau, t_hit, [&](int x, int y, int z) { return sample_t(x, y, z); }, constant);
  return RGB(float(sum[0]), float(sum[1]), float(sum[2]));
}

const RgbGrid::Spectra& RgbGrid::spectra() const {
  SpectraOnce& cache = *spectra_;
  std::call_once(cache.once, [&] {
    if (space) {  // by the space's own table
      LazyRGBToSpectrumTable table(*space);
      auto convert = [&](const std::vector<RGB>& from, std::vector<UnboundedSpectrum>& to) {
        to.reserve(from.size());
        for (const RGB& c : from) to.push_back(unbounded_spectrum_in(table, {double(c[0]), double(c[1]), double(c[2])}));
      };
      convert(own_a, cache.spectra.a);
      convert(own_s, cache.spectra.s);
      convert(own_Le, cache.spectra.Le);
      cache.spectra.white = space;
      cache.spectra.white_scale = float(1.0 / illuminant_luminance(space->illuminant));
      return;
    }
    auto convert = [](const std::vector<RGB>& from, std::vector<UnboundedSpectrum>& to) {
      to.reserve(from.size());
      for (const RGB& c : from) to.push_back(unbounded_spectrum_of(c));
    };
    convert(sigma_a, cache.spectra.a);
    convert(sigma_s, cache.spectra.s);
    convert(Le, cache.spectra.Le);
  });
  return cache.spectra;
}

// (a coefficient not given is pbrt-v4's constant spectrum: constant_a and
// constant_s are grey)
Spectrum RgbGrid::sample_t(int x, int y, int z, const Spectra& sp, const SampledWavelengths& l) const {
  if (!inside(x, y, z)) return Spectrum(0.f);
  const size_t i = offset(x, y, z);
  return (sp.a.empty() ? Spectrum(0.f) : sp.a[i].at(l)) + (sp.s.empty() ? Spectrum(0.f) : sp.s[i].at(l));
}

void RgbGrid::at(const Vec3& p, const SampledWavelengths& l, Spectrum* a, Spectrum* s) const {
  int cell[3];
  double f[3];
  *a = *s = Spectrum(0.f);
  if (!locate(p, cell, f)) return;
  const Spectra& sp = spectra();
  auto pick = [&](const std::vector<UnboundedSpectrum>& grid) {
    return [&](int x, int y, int z) { return inside(x, y, z) ? grid[offset(x, y, z)].at(l) : Spectrum(0.f); };
  };
  *a = Spectrum(constant_a[0]) + (sp.a.empty() ? Spectrum(0.f) : trilinear(cell, f, pick(sp.a)));
  *s = Spectrum(constant_s[0]) + (sp.s.empty() ? Spectrum(0.f) : trilinear(cell, f, pick(sp.s)));
}

Spectrum RgbGrid::Le_at(const Vec3& p, const SampledWavelengths& l) const {
  int cell[3];
  double f[3];
  if (Le.empty() || !locate(p, cell, f)) return Spectrum(0.f);
  const Spectra& sp = spectra();
  Spectrum white;
  if (sp.white)
    for (int i = 0; i < kSpectrumSamples; ++i) white[i] = sp.white->illuminant(l.nm[size_t(i)]) * sp.white_scale;
  else
    white = white_illuminant(l);
  return trilinear(cell, f, [&](int x, int y, int z) { return inside(x, y, z) ? sp.Le[offset(x, y, z)].at(l) : Spectrum(0.f); }) *
         white;
}

Spectrum RgbGrid::integrate(const Vec3& o, const Vec3& d, float t0, float t1, int c, float tau,
                            const SampledWavelengths& l, float* t_hit) const {
  const Spectra& sp = spectra();
  const float k = constant_a[0] + constant_s[0];
  float constant[kSpectrumSamples];
  std::fill(constant, constant + kSpectrumSamples, k);
  const std::array<double, kSpectrumSamples> sum = integrate_channels<kSpectrumSamples>(
      frame(), o, d, t0, t1, c, tau, t_hit, [&](int x, int y, int z) { return sample_t(x, y, z, sp, l); }, constant);
  Spectrum depth;
  for (int i = 0; i < kSpectrumSamples; ++i) depth[i] = float(sum[size_t(i)]);
  return depth;
}

}  // namespace lantern
