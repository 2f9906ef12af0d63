// Writes valid tabulated BSDF files (the tensor format of
// material/measured_bsdf.h) of a known analytic BRDF: a microfacet BRDF
// over a GGX distribution, tabulated as the format defines its fields
// (Dupuy & Jakob 2018): D over the unit square of normals, the projected
// area sigma(wo) = cos(theta_o) (1 + Lambda(wo)), the visible normals'
// density per outgoing direction, and over the warped square the values
// f(wo, wi) 4 sigma(wo) cos(theta_i) / D(wm), with their luminance (mean)
// for sampling. The public files are large; these are small and exact
// up to the grid's interpolation.
#pragma once

#include <cstring>
#include <fstream>
#include <functional>
#include <string>
#include <vector>

#include "material/microfacet.h"
#include "material/tensor_file.h"
#include "math/catmull_rom.h"
#include "math/piecewise_linear_2d.h"

namespace lantern::tabulated {

struct Grid {
  int ndf = 64;      // D's and sigma's grids: ndf x ndf
  int warp = 32;     // the visible normals' and the values' grids
  int theta_i = 10;  // outgoing elevations, 0 to 85 degrees
  int phi_i = 1;     // outgoing azimuths: 1 (isotropic) or more over [-pi, pi]
  std::vector<float> wavelengths = {360.f, 420.f, 480.f, 540.f, 600.f, 660.f, 720.f, 830.f};
};

// f(wo, wi, nm): the BRDF's value at one wavelength, both directions above.
using Brdf = std::function<float(const Vec3& wo, const Vec3& wi, float nm)>;

inline Vec3 from_square(float u_theta, float u_phi) {
  const float theta = u_theta * u_theta * 0.5f * kPi, phi = (2.f * u_phi - 1.f) * kPi;
  return Vec3(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta));
}

template <class T>
std::vector<uint8_t> raw(const std::vector<T>& v) {
  std::vector<uint8_t> b(v.size() * sizeof(T));
  if (!b.empty()) std::memcpy(b.data(), v.data(), b.size());
  return b;
}

inline std::vector<uint8_t> file_bytes(const TrowbridgeReitz& d, const Brdf& f, const Grid& g) {
  std::vector<float> theta_i, phi_i;
  for (int t = 0; t < g.theta_i; ++t) theta_i.push_back(glm::radians(85.f) * float(t) / float(g.theta_i - 1));
  for (int p = 0; p < g.phi_i; ++p)
    phi_i.push_back(g.phi_i == 1 ? 0.f : -kPi + 2.f * kPi * float(p) / float(g.phi_i - 1));
  const bool isotropic = g.phi_i <= 2;
  const int n = g.ndf, w = g.warp, nw = int(g.wavelengths.size());
  auto u_of = [](int i, int count) { return float(i) / float(count - 1); };
  std::vector<float> ndf(size_t(n * n)), sigma(size_t(n * n));
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x) {
      const Vec3 v = from_square(u_of(x, n), u_of(y, n));
      ndf[size_t(y * n + x)] = d.D(v);
      sigma[size_t(y * n + x)] = std::fmax(v.z, 0.f) * (1.f + d.lambda(v));
    }
  const size_t slices = size_t(g.phi_i * g.theta_i), grid = size_t(w * w);
  std::vector<float> vndf(slices * grid), spectra(slices * size_t(nw) * grid), lum(slices * grid);
  for (int p = 0; p < g.phi_i; ++p)
    for (int t = 0; t < g.theta_i; ++t) {
      const size_t s = size_t(p * g.theta_i + t);
      const float st = std::sin(theta_i[size_t(t)]);
      const Vec3 wo(st * std::cos(phi_i[size_t(p)]), st * std::sin(phi_i[size_t(p)]), std::cos(theta_i[size_t(t)]));
      const float phi_o = std::atan2(wo.y, wo.x);
      // The visible normals' density over the square: D_wo(wm) times the
      // square's Jacobian 2 pi^2 u sin(theta_m).
      for (int y = 0; y < w; ++y)
        for (int x = 0; x < w; ++x) {
          Vec3 m = from_square(u_of(x, w), u_of(y, w));
          if (isotropic)
            m = Vec3(m.x * std::cos(phi_o) - m.y * std::sin(phi_o), m.x * std::sin(phi_o) + m.y * std::cos(phi_o), m.z);
          const float jac = 2.f * kPi * kPi * u_of(x, w) * std::sqrt(m.x * m.x + m.y * m.y);
          vndf[s * grid + size_t(y * w + x)] = std::fmax(d.D(wo, m), 0.f) * jac;
        }
      // The values over the square the visible normals' warp maps from.
      const PiecewiseLinear2D warp(&vndf[s * grid], w, w, {}, true);
      const float sig = std::fmax(wo.z, 0.f) * (1.f + d.lambda(wo));
      for (int y = 0; y < w; ++y)
        for (int x = 0; x < w; ++x) {
          const Vec2 um = warp.sample(Vec2(u_of(x, w), u_of(y, w)), nullptr).p;
          Vec3 m = from_square(um.x, um.y);
          if (isotropic)
            m = Vec3(m.x * std::cos(phi_o) - m.y * std::sin(phi_o), m.x * std::sin(phi_o) + m.y * std::cos(phi_o), m.z);
          const Vec3 wi = -wo + 2.f * glm::dot(wo, m) * m;
          float sum = 0.f;
          for (int k = 0; k < nw; ++k) {
            const float dm = d.D(m);
            const float v = wi.z > 0.f && dm > 0.f ? f(wo, wi, g.wavelengths[size_t(k)]) * 4.f * sig * wi.z / dm : 0.f;
            spectra[(s * size_t(nw) + size_t(k)) * grid + size_t(y * w + x)] = v;
            sum += v;
          }
          lum[s * grid + size_t(y * w + x)] = sum / float(nw);
        }
    }
  using T = TensorFile::Type;
  const std::string about = "GGX test BRDF";
  auto u64 = [](size_t v) { return uint64_t(v); };
  return tensor_file_bytes({
      {"description", T::UInt8, {about.size()}, std::vector<uint8_t>(about.begin(), about.end())},
      {"jacobian", T::UInt8, {1}, {1}},
      {"theta_i", T::Float32, {theta_i.size()}, raw(theta_i)},
      {"phi_i", T::Float32, {phi_i.size()}, raw(phi_i)},
      {"wavelengths", T::Float32, {g.wavelengths.size()}, raw(g.wavelengths)},
      {"ndf", T::Float32, {u64(n), u64(n)}, raw(ndf)},
      {"sigma", T::Float32, {u64(n), u64(n)}, raw(sigma)},
      {"vndf", T::Float32, {phi_i.size(), theta_i.size(), u64(w), u64(w)}, raw(vndf)},
      {"luminance", T::Float32, {phi_i.size(), theta_i.size(), u64(w), u64(w)}, raw(lum)},
      {"spectra", T::Float32, {phi_i.size(), theta_i.size(), u64(nw), u64(w), u64(w)}, raw(spectra)},
  });
}

inline void write_file(const std::string& path, const std::vector<uint8_t>& bytes) {
  std::ofstream out(path, std::ios::binary);
  out.write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
}

// pbrt-v3's Fourier BSDF files ("SCATFUN", version 1) of a BSDF given as
// colour, f(wo, wi) in importance transport (the files' convention; the
// reader divides transmitted radiance by the index squared): zenith
// cosines at Chebyshev-Lobatto nodes over [-1, 1] (0 among them), and for
// each pair the cosine series of f |mu_i| over the azimuth difference by
// the midpoint rule, cut where the luminance's terms fall below 1e-5 of
// its largest. Channels: luminance, red, blue.
using ColourBsdf = std::function<RGB(const Vec3& wo, const Vec3& wi)>;

inline std::vector<uint8_t> fourier_file_bytes(const ColourBsdf& f, float eta, int n_mu = 41, int m_max = 96) {
  std::vector<float> mu(static_cast<size_t>(n_mu), 0.f);
  for (int j = 0; j < n_mu; ++j)
    mu[size_t(j)] = j == (n_mu - 1) / 2 ? 0.f : -std::cos(kPi * float(j) / float(n_mu - 1));
  const size_t cells = size_t(n_mu) * size_t(n_mu);
  std::vector<float> a, a0(cells, 0.f), cdf;
  std::vector<int32_t> offset_and_length;
  constexpr int kPhi = 256;
  for (int o = 0; o < n_mu; ++o)
    for (int i = 0; i < n_mu; ++i) {
      const float mo = mu[size_t(o)], mi = mu[size_t(i)];
      const Vec3 wo(std::sqrt(std::fmax(0.f, 1.f - mo * mo)), 0.f, mo);
      const float si = std::sqrt(std::fmax(0.f, 1.f - mi * mi));
      std::vector<double> coef(size_t(3 * m_max), 0.0);  // luminance, red, blue
      for (int j = 0; j < kPhi; ++j) {
        const float phi = kPi * (float(j) + 0.5f) / float(kPhi);
        const Vec3 wi = -Vec3(si * std::cos(phi), si * std::sin(phi), mi);
        const RGB v = wo.z == 0.f || wi.z == 0.f ? RGB(0.f) : f(wo, wi) * std::fabs(mi);
        const double ch[3] = {0.212671 * v[0] + 0.715160 * v[1] + 0.072169 * v[2], v[0], v[2]};
        double prev = std::cos(phi), cur = 1.0;  // cos(k phi) by its recurrence
        for (int k = 0; k < m_max; ++k) {
          const double w = (k == 0 ? 1.0 : 2.0) * cur / double(kPhi);
          for (int c = 0; c < 3; ++c) coef[size_t(c * m_max + k)] += w * ch[c];
          const double next = 2.0 * std::cos(phi) * cur - prev;
          prev = cur, cur = next;
        }
      }
      double largest = 0.0;
      for (int k = 0; k < m_max; ++k) largest = std::max(largest, std::fabs(coef[size_t(k)]));
      int order = 0;
      for (int k = 0; k < m_max; ++k)
        if (largest > 0.0 && std::fabs(coef[size_t(k)]) > 1e-5 * largest) order = k + 1;
      offset_and_length.push_back(int32_t(a.size()));
      offset_and_length.push_back(order);
      for (int c = 0; c < 3; ++c)
        for (int k = 0; k < order; ++k) a.push_back(float(coef[size_t(c * m_max + k)]));
      a0[size_t(o * n_mu + i)] = order > 0 ? float(coef[0]) : 0.f;
    }
  for (int o = 0; o < n_mu; ++o) {
    std::vector<float> row;
    integrate_catmull_rom(mu, &a0[size_t(o * n_mu)], &row);
    cdf.insert(cdf.end(), row.begin(), row.end());
  }
  std::vector<uint8_t> out = {'S', 'C', 'A', 'T', 'F', 'U', 'N', 1};
  auto put = [&](const auto& v) {
    const auto b = raw(v);
    out.insert(out.end(), b.begin(), b.end());
  };
  put(std::vector<int32_t>{1, n_mu, int32_t(a.size()), m_max, 3, 1, 0, 0, 0});
  put(std::vector<float>{eta});
  put(std::vector<int32_t>{0, 0, 0, 0});
  put(mu), put(cdf), put(offset_and_length), put(a);
  return out;
}

// The scene the tabulated materials' tests render: a sphere of `material`
// on a diffuse floor under a disk light and a dim sky, 24 x 16 pixels.
inline std::string sphere_on_floor(const std::string& material) {
  return R"(
LookAt 0 -3 1.4  0 0 0.5  0 0 1
Camera "perspective" "float fov" 34
Film "rgb" "integer xresolution" 24 "integer yresolution" 16
Sampler "independent"
WorldBegin
AttributeBegin
  AreaLightSource "diffuse" "rgb L" [10 10 10]
  Translate 0.8 -0.6 2.4
  ReverseOrientation
  Shape "disk" "float radius" 0.5
AttributeEnd
LightSource "infinite" "rgb L" [0.2 0.2 0.2]
Material "diffuse" "rgb reflectance" [0.6 0.3 0.2]
Shape "trianglemesh" "point3 P" [-5 -5 0  5 -5 0  5 5 0  -5 5 0] "integer indices" [0 1 2 0 2 3]
Translate 0 0 0.5
)" + material + "\nShape \"sphere\" \"float radius\" 0.5\n";
}

}  // namespace lantern::tabulated
