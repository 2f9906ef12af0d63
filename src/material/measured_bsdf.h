// pbrt-v4's measured material: a BRDF tabulated in the RGL's format
// (Dupuy & Jakob 2018). A file holds the microfacet distribution D over
// the unit square u_m = (sqrt(2 theta_m / pi), phi_m / 2 pi + 1/2), the
// projected area sigma(wo), the visible normals' distribution per
// outgoing direction as a warp from a second unit square, and over that
// second square the BRDF's spectra (and their luminance, for sampling):
//   f(wo, wi) = spectra(R^-1(u_m)) D(u_m) / (4 sigma(wo) cos theta_i)
// (their eq. 8), sampled by warping u through the luminance, then through
// the visible normals, then reflecting wo. Reflection only, two-sided.
#pragma once

#include <array>
#include <memory>
#include <string>
#include <vector>

#include "color/sampled_wavelengths.h"
#include "material/bsdf_common.h"
#include "math/piecewise_linear_2d.h"

namespace lantern {

// One file's tables, shared by every material that names it.
struct MeasuredBRDF {
  std::string path;
  bool isotropic = true;  // phi_i holds one or two values: tables follow phi_m - phi_o
  std::vector<float> wavelengths;
  PiecewiseLinear2D ndf, sigma;  // values
  PiecewiseLinear2D vndf;        // warp, by (phi_o, theta_o)
  PiecewiseLinear2D luminance;   // warp, by (phi_o, theta_o)
  PiecewiseLinear2D spectra;     // values, by (phi_o, theta_o, wavelength)
  PiecewiseLinear2D rgb;         // the RGB renderer's: by (phi_o, theta_o, channel)

  // Reads and checks a tensor file; throws std::runtime_error naming the
  // file and what is wrong.
  static std::shared_ptr<const MeasuredBRDF> load(const std::string& path);
  size_t memory_bytes() const;
};

struct MeasuredBSDF {
  const MeasuredBRDF* brdf = nullptr;
  std::array<float, kSpectrumSamples> nm{};  // the sample's wavelengths; zeros: RGB

  static constexpr bool kAlwaysSpecular = false;
  static constexpr bool kReadsComponentNumber = false;  // sample_f draws with u alone
  bool is_specular() const { return false; }

  Spectrum f(const Vec3& wo, const Vec3& wi, TransportMode) const;
  std::optional<BSDFSample> sample_f(const Vec3& wo, float, Vec2 u, TransportMode, Lobes lobes = Lobes::All) const;
  float pdf(const Vec3& wo, const Vec3& wi, TransportMode, Lobes lobes = Lobes::All) const;

 private:
  Spectrum values(Vec2 u, float phi_o, float theta_o) const;
};

}  // namespace lantern
