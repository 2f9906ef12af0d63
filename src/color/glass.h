// The optical glasses pbrt-v4 names (`glass-BK7`, `glass-F11`, ...): their
// refractive index against wavelength, by the Sellmeier dispersion formula
// with the coefficients of the manufacturer's catalogue.
#pragma once

#include <optional>
#include <string_view>

namespace lantern {

// n^2(l) = 1 + sum_i B_i l^2 / (l^2 - C_i), l in micrometres
// (Sellmeier 1871; the form and coefficients of the SCHOTT optical glass
// data sheets).
struct SellmeierGlass {
  double B[3], C[3];
  double index(double nm) const;
};

// The glass behind one of pbrt-v4's names (glass-BK7, glass-BAF10,
// glass-FK51A, glass-LASF9, glass-F5, glass-F10, glass-F11: SCHOTT's N-BK7,
// N-BAF10, N-FK51A, N-LASF9, N-SF5, N-SF10 and SF11), or nothing.
std::optional<SellmeierGlass> named_glass(std::string_view name);

// The wavelength glass catalogues quote n_d at: the helium d line.
constexpr double kHeliumDLine = 587.5618;

}  // namespace lantern
