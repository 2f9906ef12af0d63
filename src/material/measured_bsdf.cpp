#include "material/measured_bsdf.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <stdexcept>

#include "color/cie1931.h"
#include "material/tensor_file.h"

namespace lantern {

namespace {

// The files' unit square (Dupuy & Jakob 2018, sec. 4): theta by its square
// root, so that grazing angles get no more cells than the pole.
float theta_to_u(float theta) { return std::sqrt(theta * (2.f / kPi)); }
float phi_to_u(float phi) { return phi * kInv2Pi + 0.5f; }
float u_to_theta(float u) { return u * u * (0.5f * kPi); }
float u_to_phi(float u) { return (2.f * u - 1.f) * kPi; }

float theta_of(const Vec3& w) { return std::acos(std::clamp(w.z, -1.f, 1.f)); }
float phi_of(const Vec3& w) { return std::atan2(w.y, w.x); }

// The Jacobian from the unit square to solid angle, 2 pi^2 u sin(theta),
// kept away from 0 at the pole as the format's own renderers keep it.
float square_to_solid_angle(float u_theta, float sin_theta) {
  return max_num(2.f * kPi * kPi * u_theta * sin_theta, 1e-6f);
}

std::string shape_text(const TensorFile::Field& f) {
  std::string s = "[";
  for (size_t i = 0; i < f.shape.size(); ++i) s += (i ? ", " : "") + std::to_string(f.shape[i]);
  return s + "]";
}

// The sRGB of each tabulated wavelength's hat function (1 there, falling
// linearly to 0 at its neighbours, held at the ends): the RGB of a
// tabulated spectrum is then a weighted sum, since reflectance_rgb is linear.
std::vector<RGB> wavelength_basis_rgb(const std::vector<float>& w) {
  std::vector<RGB> basis;
  for (size_t k = 0; k < w.size(); ++k) {
    basis.push_back(reflectance_rgb([&](double nm) {
      const double x = std::clamp(nm, double(w.front()), double(w.back()));
      if (k > 0 && x < w[k - 1]) return 0.0;
      if (k + 1 < w.size() && x > w[k + 1]) return 0.0;
      if (x <= w[k]) return k == 0 ? 1.0 : (x - w[k - 1]) / (double(w[k]) - w[k - 1]);
      return k + 1 == w.size() ? 1.0 : (double(w[k + 1]) - x) / (double(w[k + 1]) - w[k]);
    }));
  }
  return basis;
}

}  // namespace

std::shared_ptr<const MeasuredBRDF> MeasuredBRDF::load(const std::string& path) {
  const TensorFile file(path);
  auto b = std::make_shared<MeasuredBRDF>();
  b->path = path;
  const std::vector<float> theta_i = file.floats("theta_i", 1), phi_i = file.floats("phi_i", 1);
  b->wavelengths = file.floats("wavelengths", 1);
  const TensorFile::Field& ndf = file.field("ndf", TensorFile::Type::Float32, 2);
  const TensorFile::Field& sigma = file.field("sigma", TensorFile::Type::Float32, 2);
  const TensorFile::Field& vndf = file.field("vndf", TensorFile::Type::Float32, 4);
  const TensorFile::Field& lum = file.field("luminance", TensorFile::Type::Float32, 4);
  const TensorFile::Field& spec = file.field("spectra", TensorFile::Type::Float32, 5);
  auto fail = [&](const std::string& what) { throw std::runtime_error(path + ": " + what); };
  if (theta_i.empty() || phi_i.empty() || b->wavelengths.empty())
    fail("theta_i, phi_i and wavelengths must not be empty");
  const uint64_t np = phi_i.size(), nt = theta_i.size(), nw = b->wavelengths.size();
  auto check = [&](const TensorFile::Field& f, const char* name, std::vector<uint64_t> leading) {
    for (size_t i = 0; i < leading.size(); ++i)
      if (f.shape[i] != leading[i])
        fail(std::string("field \"") + name + "\" has shape " + shape_text(f) + " (expected phi_i, theta_i" +
             (leading.size() > 2 ? ", wavelengths" : "") + " counts first)");
    for (size_t i = f.shape.size() - 2; i < f.shape.size(); ++i)
      if (f.shape[i] < 2)
        fail(std::string("field \"") + name + "\" has shape " + shape_text(f) + " (expected a grid of at least 2 x 2)");
  };
  check(ndf, "ndf", {}), check(sigma, "sigma", {});
  check(vndf, "vndf", {np, nt}), check(lum, "luminance", {np, nt}), check(spec, "spectra", {np, nt, nw});
  if (lum.shape[2] != spec.shape[3] || lum.shape[3] != spec.shape[4])
    fail("fields \"luminance\" " + shape_text(lum) + " and \"spectra\" " + shape_text(spec) + " must share their grid");
  for (const std::vector<float>* v : {&theta_i, &phi_i, static_cast<const std::vector<float>*>(&b->wavelengths)})
    for (size_t i = 1; i < v->size(); ++i)
      if (!((*v)[i] > (*v)[i - 1])) fail("theta_i, phi_i and wavelengths must be increasing");
  b->isotropic = np <= 2;
  if (!b->isotropic && std::lround(2.0 * kPi / double(phi_i.back() - phi_i.front())) != 1)
    fail("phi_i covers part of the circle (a symmetry reduction), which is not supported (nor by pbrt-v4)");

  auto floats = [](const TensorFile::Field& f) {
    std::vector<float> v(f.bytes.size() / 4);
    std::memcpy(v.data(), f.bytes.data(), v.size() * 4);
    return v;
  };
  const std::vector<std::vector<float>> angles = {phi_i, theta_i};
  b->ndf = PiecewiseLinear2D(floats(ndf).data(), int(ndf.shape[1]), int(ndf.shape[0]), {}, false);
  b->sigma = PiecewiseLinear2D(floats(sigma).data(), int(sigma.shape[1]), int(sigma.shape[0]), {}, false);
  b->vndf = PiecewiseLinear2D(floats(vndf).data(), int(vndf.shape[3]), int(vndf.shape[2]), angles, true);
  b->luminance = PiecewiseLinear2D(floats(lum).data(), int(lum.shape[3]), int(lum.shape[2]), angles, true);
  const std::vector<float> s = floats(spec);
  const int nx = int(spec.shape[4]), ny = int(spec.shape[3]);
  b->spectra = PiecewiseLinear2D(s.data(), nx, ny, {phi_i, theta_i, b->wavelengths}, false);

  // The RGB renderer reads each node's spectrum as a reflectance under the
  // colour space's white, as a spectral renderer shows it under white light.
  const std::vector<RGB> basis = wavelength_basis_rgb(b->wavelengths);
  const size_t grid = size_t(nx) * size_t(ny);
  std::vector<float> rgb(size_t(np * nt) * 3 * grid, 0.f);
  for (size_t a = 0; a < size_t(np * nt); ++a)
    for (size_t k = 0; k < size_t(nw); ++k)
      for (size_t g = 0; g < grid; ++g) {
        const float v = s[(a * size_t(nw) + k) * grid + g];
        for (size_t c = 0; c < 3; ++c) rgb[(a * 3 + c) * grid + g] += v * basis[k][int(c)];
      }
  b->rgb = PiecewiseLinear2D(rgb.data(), nx, ny, {phi_i, theta_i, {0.f, 1.f, 2.f}}, false);
  return b;
}

size_t MeasuredBRDF::memory_bytes() const {
  return sizeof(*this) + wavelengths.capacity() * sizeof(float) + ndf.memory_bytes() + sigma.memory_bytes() +
         vndf.memory_bytes() + luminance.memory_bytes() + spectra.memory_bytes() + rgb.memory_bytes();
}

Spectrum MeasuredBSDF::values(Vec2 u, float phi_o, float theta_o) const {
  Spectrum v;
  if (nm[0] == 0.f) {
    float rgb[3];
    for (int c = 0; c < 3; ++c) {
      const float p[3] = {phi_o, theta_o, float(c)};
      rgb[c] = max_num(brdf->rgb.evaluate(u, p), 0.f);
    }
    return Spectrum(rgb[0], rgb[1], rgb[2], rgb[1]);
  }
  for (int i = 0; i < kSpectrumSamples; ++i) {
    const float p[3] = {phi_o, theta_o, nm[size_t(i)]};
    v[i] = max_num(brdf->spectra.evaluate(u, p), 0.f);
  }
  return v;
}

Spectrum MeasuredBSDF::f(const Vec3& wo_in, const Vec3& wi_in, TransportMode) const {
  if (!same_hemisphere(wo_in, wi_in)) return Spectrum(0.f);
  const Vec3 wo = wo_in.z < 0.f ? -wo_in : wo_in, wi = wo_in.z < 0.f ? -wi_in : wi_in;
  Vec3 wm = wo + wi;
  if (glm::dot(wm, wm) == 0.f) return Spectrum(0.f);
  wm = glm::normalize(wm);
  const float theta_o = theta_of(wo), phi_o = phi_of(wo);
  const Vec2 u_wo(theta_to_u(theta_o), phi_to_u(phi_o));
  Vec2 u_wm(theta_to_u(theta_of(wm)), phi_to_u(brdf->isotropic ? phi_of(wm) - phi_o : phi_of(wm)));
  u_wm.y -= std::floor(u_wm.y);
  const float angles[2] = {phi_o, theta_o};
  const PiecewiseLinear2D::Sample ui = brdf->vndf.invert(u_wm, angles);
  const float den = 4.f * brdf->sigma.evaluate(u_wo, nullptr) * wi.z;
  if (!(den > 0.f)) return Spectrum(0.f);
  return values(ui.p, phi_o, theta_o) * (brdf->ndf.evaluate(u_wm, nullptr) / den);
}

std::optional<BSDFSample> MeasuredBSDF::sample_f(const Vec3& wo_in, float, Vec2 u, TransportMode, Lobes lobes) const {
  if (!has(lobes, Lobes::Reflection) || wo_in.z == 0.f) return std::nullopt;
  const bool flip = wo_in.z < 0.f;
  const Vec3 wo = flip ? -wo_in : wo_in;
  const float theta_o = theta_of(wo), phi_o = phi_of(wo);
  const float angles[2] = {phi_o, theta_o};
  const PiecewiseLinear2D::Sample l = brdf->luminance.sample(u, angles);
  const PiecewiseLinear2D::Sample m = brdf->vndf.sample(l.p, angles);
  const float phi_m = u_to_phi(m.p.y) + (brdf->isotropic ? phi_o : 0.f), theta_m = u_to_theta(m.p.x);
  const float sin_m = std::sin(theta_m);
  const Vec3 wm(sin_m * std::cos(phi_m), sin_m * std::sin(phi_m), std::cos(theta_m));
  const Vec3 wi = reflect(wo, wm);
  const Vec2 u_wo(theta_to_u(theta_o), phi_to_u(phi_o));
  const float den = 4.f * brdf->sigma.evaluate(u_wo, nullptr) * wi.z;
  const float pdf = m.pdf * l.pdf / (4.f * glm::dot(wo, wm) * square_to_solid_angle(m.p.x, sin_m));
  if (wi.z <= 0.f || !(den > 0.f) || !(pdf > 0.f) || !std::isfinite(pdf)) return std::nullopt;
  BSDFSample s;
  s.f = values(l.p, phi_o, theta_o) * (brdf->ndf.evaluate(m.p, nullptr) / den);
  s.wi = flip ? -wi : wi;
  s.pdf = pdf;
  return s;
}

float MeasuredBSDF::pdf(const Vec3& wo_in, const Vec3& wi_in, TransportMode, Lobes lobes) const {
  if (!has(lobes, Lobes::Reflection) || !same_hemisphere(wo_in, wi_in)) return 0.f;
  const Vec3 wo = wo_in.z < 0.f ? -wo_in : wo_in, wi = wo_in.z < 0.f ? -wi_in : wi_in;
  Vec3 wm = wo + wi;
  if (glm::dot(wm, wm) == 0.f) return 0.f;
  wm = glm::normalize(wm);
  const float theta_o = theta_of(wo), phi_o = phi_of(wo);
  Vec2 u_wm(theta_to_u(theta_of(wm)), phi_to_u(brdf->isotropic ? phi_of(wm) - phi_o : phi_of(wm)));
  u_wm.y -= std::floor(u_wm.y);
  const float angles[2] = {phi_o, theta_o};
  const PiecewiseLinear2D::Sample ui = brdf->vndf.invert(u_wm, angles);
  const float sin_m = std::sqrt(wm.x * wm.x + wm.y * wm.y);
  const float pdf =
      ui.pdf * brdf->luminance.evaluate(ui.p, angles) / (4.f * glm::dot(wi, wm) * square_to_solid_angle(u_wm.x, sin_m));
  return std::isfinite(pdf) ? pdf : 0.f;
}

}  // namespace lantern
