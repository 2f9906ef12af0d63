#include "color/rgb_spectrum_fit.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>

#include "color/cie1931.h"

namespace lantern {

namespace {

using Vec3d = std::array<double, 3>;

// CIELAB's companding function and its derivative.
constexpr double kDelta = 6.0 / 29.0;
double lab_f(double t) {
  return t > kDelta * kDelta * kDelta ? std::cbrt(t) : t / (3.0 * kDelta * kDelta) + 4.0 / 29.0;
}
double lab_df(double t) {
  return t > kDelta * kDelta * kDelta ? 1.0 / (3.0 * std::cbrt(t * t)) : 1.0 / (3.0 * kDelta * kDelta);
}

Vec3d lab(const Vec3d& xyz, const Vec3d& white) {
  const double fx = lab_f(xyz[0] / white[0]), fy = lab_f(xyz[1] / white[1]), fz = lab_f(xyz[2] / white[2]);
  return {116.0 * fy - 16.0, 500.0 * (fx - fy), 200.0 * (fy - fz)};
}

// d lab / d xyz, row-major.
std::array<double, 9> lab_jacobian(const Vec3d& xyz, const Vec3d& white) {
  const double dx = lab_df(xyz[0] / white[0]) / white[0], dy = lab_df(xyz[1] / white[1]) / white[1],
               dz = lab_df(xyz[2] / white[2]) / white[2];
  return {0.0, 116.0 * dy, 0.0, 500.0 * dx, -500.0 * dy, 0.0, 0.0, 200.0 * dy, -200.0 * dz};
}

// Solves the 3x3 system a x = b (row-major) by Cramer's rule; false if singular.
bool solve3(const std::array<double, 9>& a, const Vec3d& b, Vec3d* x) {
  auto det = [](const std::array<double, 9>& m) {
    return m[0] * (m[4] * m[8] - m[5] * m[7]) - m[1] * (m[3] * m[8] - m[5] * m[6]) + m[2] * (m[3] * m[7] - m[4] * m[6]);
  };
  const double d = det(a);
  if (!(std::fabs(d) > 1e-30)) return false;
  for (size_t k = 0; k < 3; ++k) {
    std::array<double, 9> m = a;
    for (size_t r = 0; r < 3; ++r) m[3 * r + k] = b[r];
    (*x)[k] = det(m) / d;
  }
  return true;
}

double norm(const Vec3d& v) { return std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]); }

}  // namespace

SigmoidFitter::SigmoidFitter(const ColorSpace& cs) : cs_(cs) {
  double white_y = 0.0;
  for (int k = 0; k < kSamples; ++k) {
    const double nm = double(kLambdaMin) + double(k);
    const double w = (k == 0 || k == kSamples - 1) ? 0.5 : 1.0;  // the trapezoidal rule
    const Vec3 cmf = cie1931_cmf(float(nm));
    const double e = w * double(cs.illuminant(float(nm)));
    t_[size_t(k)] = (nm - double(kLambdaMin)) / double(kLambdaMax - kLambdaMin);
    for (int c = 0; c < 3; ++c) xyz_[size_t(k)][size_t(c)] = e * double(cmf[c]);
    white_y += e * double(cmf[1]);
  }
  for (auto& v : xyz_)
    for (double& x : v) x /= white_y;
}

Vec3d SigmoidFitter::xyz_of(const Vec3d& c, std::array<double, 9>* jacobian) const {
  Vec3d xyz{0.0, 0.0, 0.0};
  if (jacobian) jacobian->fill(0.0);
  for (size_t k = 0; k < size_t(kSamples); ++k) {
    const double t = t_[k], x = (c[0] * t + c[1]) * t + c[2];
    const double q = 1.0 / std::sqrt(1.0 + x * x);
    const double s = 0.5 + 0.5 * x * q;
    for (size_t r = 0; r < 3; ++r) xyz[r] += s * xyz_[k][r];
    if (jacobian) {
      const double ds = 0.5 * q * q * q;  // dS/dx
      const double dx[3] = {t * t, t, 1.0};
      for (size_t r = 0; r < 3; ++r)
        for (size_t j = 0; j < 3; ++j) (*jacobian)[3 * r + j] += ds * dx[j] * xyz_[k][r];
    }
  }
  return xyz;
}

Vec3d SigmoidFitter::rgb_of(const Vec3d& c) const { return multiply(cs_.xyz_to_rgb, xyz_of(c, nullptr)); }

SigmoidFit SigmoidFitter::fit(const Vec3d& rgb, const Vec3d& start) const {
  const Vec3d target = lab(multiply(cs_.rgb_to_xyz, rgb), cs_.white);
  SigmoidFit f;
  f.c = start;
  auto residual = [&](const Vec3d& c, std::array<double, 9>* j_xyz, Vec3d* xyz) {
    *xyz = xyz_of(c, j_xyz);
    const Vec3d l = lab(*xyz, cs_.white);
    return Vec3d{l[0] - target[0], l[1] - target[1], l[2] - target[2]};
  };
  std::array<double, 9> j_xyz;
  Vec3d xyz;
  Vec3d r = residual(f.c, &j_xyz, &xyz);
  // The paper's optimiser (rgb2spec_opt): up to 15 full Gauss-Newton
  // steps, the coefficients scaled down whenever the largest passes
  // kMaxCoefficient. A colour no spectrum reaches (near or beyond the
  // spectral locus: the far corners of rec2020's and ACES's tables) would
  // drive them to infinity, towards a box spectrum, and the table
  // interpolates between nodes: unbounded, with a line search, ACES's
  // node fits ran to 1e10 and its saturated colours came out up to 20% off
  // pbrt-v4's, whose tables are fitted so.
  for (int it = 0; it < kFitSteps && norm(r) > 1e-6; ++it) {
    // J = d lab / d xyz * d xyz / d c; the Gauss-Newton step solves J d = -r.
    const std::array<double, 9> jl = lab_jacobian(xyz, cs_.white);
    std::array<double, 9> j{};
    for (size_t a = 0; a < 3; ++a)
      for (size_t b = 0; b < 3; ++b)
        for (size_t k = 0; k < 3; ++k) j[3 * a + b] += jl[3 * a + k] * j_xyz[3 * k + b];
    Vec3d d;
    if (!solve3(j, {-r[0], -r[1], -r[2]}, &d)) break;
    Vec3d c{f.c[0] + d[0], f.c[1] + d[1], f.c[2] + d[2]};
    const double largest = std::max({c[0], c[1], c[2]});
    if (largest > kMaxCoefficient)
      for (double& x : c) x *= kMaxCoefficient / largest;
    f.c = c;
    r = residual(c, &j_xyz, &xyz);
  }
  f.residual = norm(r);
  return f;
}

std::vector<Vec3d> fit_table_column(const SigmoidFitter& fitter, const std::vector<float>& z, int res, int largest,
                                    int xi, int yi) {
  std::vector<Vec3d> column(static_cast<size_t>(res));
  const int start = res / 5;
  const double x = double(xi) / double(res - 1), y = double(yi) / double(res - 1);
  auto solve = [&](int zi, const Vec3d& from) {
    Vec3d rgb;
    rgb[size_t(largest)] = double(z[size_t(zi)]);
    rgb[size_t((largest + 1) % 3)] = x * double(z[size_t(zi)]);
    rgb[size_t((largest + 2) % 3)] = y * double(z[size_t(zi)]);
    return column[size_t(zi)] = fitter.fit(rgb, from).c;
  };
  const Vec3d mid = solve(start, {0.0, 0.0, 0.0});
  Vec3d c = mid;
  for (int zi = start + 1; zi < res; ++zi) c = solve(zi, c);
  c = mid;
  for (int zi = start - 1; zi >= 0; --zi) c = solve(zi, c);
  return column;
}

RGBToSpectrumTable fit_rgb_to_spectrum_table(const ColorSpace& cs, int res) {
  const SigmoidFitter fitter(cs);
  const std::vector<float> z = RGBToSpectrumTable::z_nodes(res);
  std::vector<float> out(RGBToSpectrumTable::index(res, 3, 0, 0, 0));
  tbb::parallel_for(0, 3 * res, [&](int task) {
    const int largest = task / res, yi = task % res;
    for (int xi = 0; xi < res; ++xi) {
      const std::vector<Vec3d> column = fit_table_column(fitter, z, res, largest, xi, yi);
      for (int zi = 0; zi < res; ++zi)
        for (size_t k = 0; k < 3; ++k)
          out[RGBToSpectrumTable::index(res, largest, zi, yi, xi) + k] = float(column[size_t(zi)][k]);
    }
  });
  return RGBToSpectrumTable(res, std::move(out));
}

LazyRGBToSpectrumTable::LazyRGBToSpectrumTable(const ColorSpace& cs, int res)
    : fitter_(cs), res_(res), z_(RGBToSpectrumTable::z_nodes(res)) {}

// The lookup of RGBToSpectrumTable::operator(), over nodes fitted on demand.
SigmoidPolynomial LazyRGBToSpectrumTable::operator()(const RGB& in) {
  RGBTableCell c;
  if (!rgb_table_cell(in, res_, z_, &c)) return SigmoidPolynomial::constant(clamp(in, 0.f, 1.f)[0]);
  return interpolate_rgb_table(c, [&](int oz, int oy, int ox, int k) {
    const int key = (c.largest * res_ + c.y + oy) * res_ + c.x + ox;
    auto it = columns_.find(key);
    if (it == columns_.end())
      it = columns_.emplace(key, fit_table_column(fitter_, z_, res_, c.largest, c.x + ox, c.y + oy)).first;
    return float(it->second[size_t(c.z + oz)][size_t(k)]);  // (as the table stores it)
  });
}

UnboundedSpectrum unbounded_spectrum_in(LazyRGBToSpectrumTable& table, const std::array<double, 3>& rgb) {
  UnboundedSpectrum u;
  const double scale = 2.0 * std::max({rgb[0], rgb[1], rgb[2]});
  if (!(scale > 0.0)) return u;
  u.shape = table(RGB(float(rgb[0] / scale), float(rgb[1] / scale), float(rgb[2] / scale)));
  u.scale = float(scale);
  return u;
}

}  // namespace lantern
