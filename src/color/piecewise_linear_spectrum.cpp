#include "color/piecewise_linear_spectrum.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "color/cie1931.h"
#include "lantern/error.h"

namespace lantern {

double PiecewiseLinearSpectrum::operator()(double lambda) const {
  if (nm.empty() || !(lambda >= nm.front()) || !(lambda <= nm.back())) return 0.0;
  const size_t i = size_t(std::upper_bound(nm.begin(), nm.end(), lambda) - nm.begin());
  if (i == nm.size()) return value.back();
  const double t = (lambda - nm[i - 1]) / (nm[i] - nm[i - 1]);
  return value[i - 1] + t * (value[i] - value[i - 1]);
}

PiecewiseLinearSpectrum spectrum_from_pairs(std::span<const double> pairs) {
  if (pairs.empty()) throw std::invalid_argument("a sampled spectrum needs (wavelength, value) pairs; none given");
  if (pairs.size() % 2 != 0)
    throw std::invalid_argument("a sampled spectrum needs (wavelength, value) pairs; found an odd number of values (" +
                                std::to_string(pairs.size()) + ")");
  PiecewiseLinearSpectrum s;
  for (size_t i = 0; i < pairs.size(); i += 2) {
    const double l = pairs[i], v = pairs[i + 1];
    if (!std::isfinite(l) || !std::isfinite(v))
      throw std::invalid_argument("pair " + std::to_string(i / 2 + 1) + " is not finite");
    if (!s.nm.empty() && !(l > s.nm.back()))
      throw std::invalid_argument("wavelengths must increase: pair " + std::to_string(i / 2 + 1) + " has " +
                                  std::to_string(l) + " nm after " + std::to_string(s.nm.back()) + " nm");
    s.nm.push_back(l);
    s.value.push_back(v);
  }
  return s;
}

PiecewiseLinearSpectrum read_spectrum_file(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw InputError({path, 0, 0}, "cannot read spectrum file");
  std::vector<double> numbers;
  std::string line;
  for (int line_no = 1; std::getline(in, line); ++line_no) {
    line = line.substr(0, line.find('#'));
    std::istringstream words(line);
    std::string w;
    while (words >> w) {
      char* end = nullptr;
      const double v = std::strtod(w.c_str(), &end);
      if (end == w.c_str() || *end != '\0')
        throw InputError({path, line_no, 0}, "\"" + printable(w) + "\" is not a number; a spectrum file holds wavelength (nm) and value pairs");
      numbers.push_back(v);
    }
  }
  try {
    return spectrum_from_pairs(numbers);
  } catch (const std::invalid_argument& e) {
    throw InputError({path, 0, 0}, e.what());
  }
}

RGB illuminant_rgb(const PiecewiseLinearSpectrum& s) {
  Vec3 xyz(0.f);
  for (int nm = 360; nm <= 830; ++nm) xyz += float(s(double(nm))) * cie1931_cmf(float(nm));
  if (!(xyz.y > 0.f)) return RGB(0.f);
  return max(xyz_to_linear_srgb(xyz / xyz.y), RGB(0.f));
}

PiecewiseLinearSpectrum blackbody_spectrum(float kelvin) {
  PiecewiseLinearSpectrum s;
  if (!(kelvin > 0.f)) return s;
  const double peak = blackbody_peak_radiance(double(kelvin));
  for (int nm = 360; nm <= 830; ++nm) {
    s.nm.push_back(double(nm));
    s.value.push_back(blackbody_radiance(double(nm), double(kelvin)) / peak);
  }
  return s;
}

double spectrum_luminance(const PiecewiseLinearSpectrum& s) {
  double y = 0.0;
  for (int nm = 360; nm <= 830; ++nm) y += s(double(nm)) * double(cie1931_cmf(float(nm)).y);
  return y;
}

}  // namespace lantern
