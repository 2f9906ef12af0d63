#include "color/optical_constants.h"

#include <algorithm>
#include <cmath>
#include <complex>
#include <map>
#include <mutex>
#include <string>
#include <vector>

#include "color/cie1931.h"

namespace lantern {

namespace {

// The tables, trimmed to the visible range and one row beyond it on each
// side. Values as published, through the refractiveindex.info database
// (public domain, CC0 1.0).

// P. B. Johnson and R. W. Christy, Optical constants of the noble metals,
// Phys. Rev. B 6, 4370-4379 (1972), Table I.
constexpr OpticalConstant kGold[] = {
    {354.2f, 1.50f, 1.866f}, {367.9f, 1.48f, 1.895f}, {381.5f, 1.46f, 1.933f}, {397.4f, 1.47f, 1.952f}, 
    {413.3f, 1.46f, 1.958f}, {430.5f, 1.45f, 1.948f}, {450.9f, 1.38f, 1.914f}, {471.4f, 1.31f, 1.849f}, 
    {495.9f, 1.04f, 1.833f}, {520.9f, 0.62f, 2.081f}, {548.6f, 0.43f, 2.455f}, {582.1f, 0.29f, 2.863f}, 
    {616.8f, 0.21f, 3.272f}, {659.5f, 0.14f, 3.697f}, {704.5f, 0.13f, 4.103f}, {756.f, 0.14f, 4.542f}, 
    {821.1f, 0.16f, 5.083f}, {892.f, 0.17f, 5.663f}};
constexpr OpticalConstant kSilver[] = {
    {354.2f, 0.10f, 1.419f}, {367.9f, 0.07f, 1.657f}, {381.5f, 0.05f, 1.864f}, {397.4f, 0.05f, 2.070f}, 
    {413.3f, 0.05f, 2.275f}, {430.5f, 0.04f, 2.462f}, {450.9f, 0.04f, 2.657f}, {471.4f, 0.05f, 2.869f}, 
    {495.9f, 0.05f, 3.093f}, {520.9f, 0.05f, 3.324f}, {548.6f, 0.06f, 3.586f}, {582.1f, 0.05f, 3.858f}, 
    {616.8f, 0.06f, 4.152f}, {659.5f, 0.05f, 4.483f}, {704.5f, 0.04f, 4.838f}, {756.f, 0.03f, 5.242f}, 
    {821.1f, 0.04f, 5.727f}, {892.f, 0.04f, 6.312f}};
constexpr OpticalConstant kCopper[] = {
    {354.2f, 1.37f, 1.916f}, {367.9f, 1.36f, 1.975f}, {381.5f, 1.33f, 2.045f}, {397.4f, 1.32f, 2.116f}, 
    {413.3f, 1.28f, 2.207f}, {430.5f, 1.25f, 2.305f}, {450.9f, 1.24f, 2.397f}, {471.4f, 1.25f, 2.483f}, 
    {495.9f, 1.22f, 2.564f}, {520.9f, 1.18f, 2.608f}, {548.6f, 1.02f, 2.577f}, {582.1f, 0.70f, 2.704f}, 
    {616.8f, 0.30f, 3.205f}, {659.5f, 0.22f, 3.747f}, {704.5f, 0.21f, 4.205f}, {756.f, 0.24f, 4.665f}, 
    {821.1f, 0.26f, 5.180f}, {892.f, 0.30f, 5.768f}};

// A. D. Rakic, Algorithm for the determination of intrinsic optical
// constants of metal films: application to aluminum, Appl. Opt. 34,
// 4755-4767 (1995).
constexpr OpticalConstant kAluminium[] = {
    {309.96f, 0.28003f, 3.7081f}, {326.28f, 0.31474f, 3.9165f}, {364.66f, 0.39877f, 4.3957f}, {413.28f, 0.52135f, 5.0008f}, 
    {442.8f, 0.60790f, 5.3676f}, {476.87f, 0.72780f, 5.7781f}, {516.6f, 0.87340f, 6.2418f}, {563.57f, 1.0728f, 6.7839f}, 
    {619.93f, 1.3660f, 7.4052f}, {652.25f, 1.5724f, 7.7354f}, {688.81f, 1.8301f, 8.0601f}, {729.32f, 2.1606f, 8.3565f}, 
    {774.91f, 2.6154f, 8.4914f}, {794.78f, 2.7675f, 8.3866f}, {815.69f, 2.7668f, 8.2573f}, {837.74f, 2.6945f, 8.1878f}, 
    {885.61f, 2.2802f, 8.1134f}};

// M. R. Querry, Optical constants, Contractor Report CRDC-CR-85034 (1985):
// brass, 70% Cu and 30% Zn.
constexpr OpticalConstant kBrass[] = {
    {360.f, 1.503f, 1.815f}, {370.f, 1.497f, 1.818f}, {380.f, 1.487f, 1.818f}, {390.f, 1.471f, 1.813f}, 
    {400.f, 1.445f, 1.805f}, {410.f, 1.405f, 1.794f}, {420.f, 1.350f, 1.786f}, {430.f, 1.278f, 1.784f}, 
    {440.f, 1.191f, 1.797f}, {450.f, 1.094f, 1.829f}, {460.f, 0.994f, 1.883f}, {470.f, 0.900f, 1.957f}, 
    {480.f, 0.816f, 2.046f}, {490.f, 0.745f, 2.145f}, {500.f, 0.686f, 2.250f}, {510.f, 0.639f, 2.358f}, 
    {520.f, 0.602f, 2.464f}, {530.f, 0.573f, 2.568f}, {540.f, 0.549f, 2.668f}, {550.f, 0.527f, 2.765f}, 
    {560.f, 0.505f, 2.860f}, {570.f, 0.484f, 2.958f}, {580.f, 0.468f, 3.059f}, {590.f, 0.460f, 3.159f}, 
    {600.f, 0.450f, 3.253f}, {610.f, 0.452f, 3.345f}, {620.f, 0.449f, 3.434f}, {630.f, 0.445f, 3.522f}, 
    {640.f, 0.444f, 3.609f}, {650.f, 0.444f, 3.695f}, {660.f, 0.445f, 3.778f}, {670.f, 0.444f, 3.860f}, 
    {680.f, 0.444f, 3.943f}, {690.f, 0.445f, 4.025f}, {700.f, 0.446f, 4.106f}, {710.f, 0.448f, 4.186f}, 
    {720.f, 0.450f, 4.266f}, {730.f, 0.452f, 4.346f}, {740.f, 0.455f, 4.424f}, {750.f, 0.457f, 4.501f}, 
    {760.f, 0.458f, 4.579f}, {770.f, 0.460f, 4.657f}, {780.f, 0.464f, 4.737f}, {790.f, 0.469f, 4.814f}};

// Transparent crystals pbrt-v4 also lists among its metals, given by
// published dispersion formulas (lambda in micrometres), tabulated here at
// 10 nm with k = 0 across the visible, where both absorb nothing to speak of.
// R. E. Stephens and I. H. Malitson, Index of refraction of magnesium oxide,
// J. Res. Natl. Bur. Stand. 49, 249-252 (1952).
double magnesium_oxide_index(double um) {
  const double l2 = um * um;
  return std::sqrt(2.956362 + 0.02195770 / (l2 - 0.01428322) - 0.01062387 * l2 - 0.0000204968 * l2 * l2);
}
// J. R. DeVore, Refractive indices of rutile and sphalerite, J. Opt. Soc.
// Am. 41, 416-419 (1951): rutile, ordinary ray.
double rutile_index(double um) {
  const double l2 = um * um;
  return std::sqrt(5.913 + 0.2441 / (l2 - 0.0803));
}
std::vector<OpticalConstant> tabulate(double (*index)(double)) {
  std::vector<OpticalConstant> table;
  for (int nm = 360; nm <= 800; nm += 10) table.push_back({float(nm), float(index(nm * 1e-3)), 0.f});
  return table;
}

// n and k at nm: linear between rows, the end rows held beyond the table.
std::pair<double, double> lookup(std::span<const OpticalConstant> table, double nm) {
  if (nm <= table.front().nm) return {table.front().n, table.front().k};
  if (nm >= table.back().nm) return {table.back().n, table.back().k};
  auto hi = std::upper_bound(table.begin(), table.end(), nm,
                             [](double x, const OpticalConstant& row) { return x < double(row.nm); });
  auto lo = hi - 1;
  const double t = (nm - lo->nm) / double(hi->nm - lo->nm);
  return {(1.0 - t) * lo->n + t * hi->n, (1.0 - t) * lo->k + t * hi->k};
}

// Gulbrandsen's parameterisation of a conductor by its normal reflectance r
// and an edge tint g in [0, 1] (JCGT 3(4), 2014, eqs. 6 and 8): g = 0 is the
// dielectric of reflectance r, g -> 1 the strongest absorber.
std::pair<double, double> conductor_from_tint(double r, double g) {
  const double s = std::sqrt(r);
  const double n = g * (1.0 - r) / (1.0 + r) + (1.0 - g) * (1.0 + s) / (1.0 - s);
  const double k2 = (r * (n + 1.0) * (n + 1.0) - (n - 1.0) * (n - 1.0)) / (1.0 - r);
  return {n, std::sqrt(std::max(k2, 0.0))};
}

// The conductor of normal reflectance r whose hemispherical average is
// closest to `average`: a scan over the tint, then a finer scan around the
// best (the average need not be monotonic in the tint). Gold's red lies
// outside the sRGB gamut (its reduced reflectance exceeds 1), so targets are
// clipped below 1 first.
std::pair<double, double> fit_channel(double r, double average) {
  r = std::clamp(r, 1e-4, 0.999);
  average = std::clamp(average, 1e-4, 0.999);
  auto error = [&](double g) {
    auto [n, k] = conductor_from_tint(r, g);
    return std::abs(fresnel_conductor_average(n, k) - average);
  };
  double best = 0.0, width = 1.0;
  for (int pass = 0; pass < 4; ++pass) {
    const double lo = std::max(best - width, 0.0), hi = std::min(best + width, 0.999999);
    double best_error = error(best);
    for (int i = 0; i <= 64; ++i) {
      const double g = lo + (hi - lo) * i / 64.0;
      if (const double e = error(g); e < best_error) best_error = e, best = g;
    }
    width = (hi - lo) / 32.0;
  }
  return conductor_from_tint(r, best);
}

}  // namespace

std::span<const OpticalConstant> optical_constants(std::string_view metal) {
  if (metal == "Au") return kGold;
  if (metal == "Ag") return kSilver;
  if (metal == "Cu") return kCopper;
  if (metal == "Al") return kAluminium;
  if (metal == "CuZn") return kBrass;
  if (metal == "MgO") {
    static const std::vector<OpticalConstant> table = tabulate(magnesium_oxide_index);
    return table;
  }
  if (metal == "TiO2") {
    static const std::vector<OpticalConstant> table = tabulate(rutile_index);
    return table;
  }
  return {};
}

double fresnel_conductor(double cos_theta, double n, double k) {
  const std::complex<double> eta(n, k);
  const double cos_i = std::clamp(cos_theta, 0.0, 1.0);
  const std::complex<double> sin2_t = (1.0 - cos_i * cos_i) / (eta * eta);
  const std::complex<double> cos_t = std::sqrt(1.0 - sin2_t);
  const std::complex<double> r_parallel = (eta * cos_i - cos_t) / (eta * cos_i + cos_t);
  const std::complex<double> r_perpendicular = (cos_i - eta * cos_t) / (cos_i + eta * cos_t);
  return 0.5 * (std::norm(r_parallel) + std::norm(r_perpendicular));
}

double fresnel_conductor_average(double n, double k) {
  // 2 * integral of F(mu) mu over [0, 1], midpoint rule; F is smooth and
  // the 256 steps agree with 4096 to 1e-6.
  constexpr int steps = 256;
  double sum = 0.0;
  for (int i = 0; i < steps; ++i) {
    const double mu = (i + 0.5) / steps;
    sum += fresnel_conductor(mu, n, k) * mu;
  }
  return 2.0 * sum / steps;
}

ConductorRGB fit_conductor_rgb(std::span<const OpticalConstant> table) {
  const RGB normal = reflectance_rgb([&](double nm) {
    auto [n, k] = lookup(table, nm);
    return fresnel_conductor(1.0, n, k);
  });
  const RGB average = reflectance_rgb([&](double nm) {
    auto [n, k] = lookup(table, nm);
    return fresnel_conductor_average(n, k);
  });
  ConductorRGB out{};
  for (int c = 0; c < 3; ++c) {
    auto [n, k] = fit_channel(double(normal[c]), double(average[c]));
    out.eta[c] = float(n);
    out.k[c] = float(k);
  }
  return out;
}

std::optional<ConductorRGB> named_conductor_rgb(std::string_view metal) {
  const auto table = optical_constants(metal);
  if (table.empty()) return std::nullopt;
  static std::mutex mutex;
  static std::map<std::string, ConductorRGB, std::less<>> fitted;
  const std::lock_guard lock(mutex);
  auto it = fitted.find(metal);
  if (it == fitted.end()) it = fitted.emplace(std::string(metal), fit_conductor_rgb(table)).first;
  return it->second;
}

}  // namespace lantern
