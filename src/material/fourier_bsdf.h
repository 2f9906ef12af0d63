// pbrt-v3's fourier material: a BSDF tabulated by Jakob et al. 2014 ("A
// Comprehensive Framework for Rendering Layered Materials") as, for each
// pair of zenith cosines (mu_i, mu_o) of a grid over [-1, 1], the cosines'
// series in the azimuth difference phi of f(wo, wi) |mu_i|, with the
// incident direction pointing at the surface (mu_i = -cos(theta_i)):
// reflection where mu_i mu_o < 0, transmission where it is positive.
// Between grid cosines the series' coefficients follow Catmull-Rom
// splines. One channel (luminance) or three (luminance, red, blue; green
// from the luminance). Sampled by the zenith cosine's spline, then the
// azimuth's series (Physically Based Rendering, 3rd ed., sec. 8.6).
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "color/sampled_wavelengths.h"
#include "material/bsdf_common.h"

namespace lantern {

// One file (pbrt-v3's "SCATFUN" format, version 1), shared by every
// material that names it.
struct FourierTable {
  std::string path;
  float eta = 1.f;  // the relative index the transmitted radiance is scaled by
  int m_max = 0, channels = 1;
  std::vector<float> mu;       // the zenith cosines, ascending
  std::vector<float> a0, cdf;  // per (o, i): the luminance's a_0, and its running integral over mu_i
  std::vector<float> a;        // every coefficient: per (o, i), `order` per channel
  std::vector<int32_t> offset, order;

  // Throws std::runtime_error naming the file and what is wrong.
  static std::shared_ptr<const FourierTable> load(const std::string& path);
  size_t memory_bytes() const;
};

struct FourierBSDF {
  const FourierTable* table = nullptr;
  SampledWavelengths lambda;  // where the tabulated colour becomes a spectrum

  static constexpr bool kAlwaysSpecular = false;
  static constexpr bool kReadsComponentNumber = false;  // sample_f draws with u alone
  bool is_specular() const { return false; }

  Spectrum f(const Vec3& wo, const Vec3& wi, TransportMode mode) const;
  std::optional<BSDFSample> sample_f(const Vec3& wo, float, Vec2 u, TransportMode mode, Lobes lobes = Lobes::All) const;
  float pdf(const Vec3& wo, const Vec3& wi, TransportMode, Lobes lobes = Lobes::All) const;
};

}  // namespace lantern
