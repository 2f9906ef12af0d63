// pbrt-v4's hair: the fibre scattering model of Chiang, Bitterli, Tappan &
// Burley 2016 ("A Practical and Controllable Hair and Fur Model for
// Production Path Tracing"), built on d'Eon, Francois, Hill, Letteri &
// Aubry 2011 ("An Energy-Conserving Hair Reflectance Model"), as pbrt-v4
// parameterises it (Pharr, Jakob & Humphreys, Physically Based Rendering,
// 4th ed., sec. 9.9).
//
// A fibre is a dielectric cylinder that absorbs inside. Light leaves it
// after p internal paths: R (p = 0), TT, TRT, and all longer paths lumped
// together. Each term is a longitudinal lobe Mp (around the mirror angle,
// tilted by the cuticle scales' angle alpha), an attenuation Ap (Fresnel
// and absorption along the path) and an azimuthal lobe Np (a trimmed
// logistic around the exit azimuth the path's geometry gives). h in
// [-1, 1] is where across the fibre's width the ray met it.
//
// Directions come in the shading frame (z = normal); the fibre's frame has
// x along the curve, z the normal, y = z x x. f includes 1 / |cos theta_i|
// with respect to the normal, so that the integrators' cosine cancels:
// scattering by a fibre does not depend on the normal a ribbon is given.
// The density is exact (sample_f's pdf is pdf()).
#pragma once

#include <array>

#include "material/bsdf_common.h"
#include "material/fresnel.h"

namespace lantern {

struct HairBSDF {
  static constexpr int kPMax = 3;

  // eta: of the fibre; sigma_a: absorption per unit of the fibre's
  // diameter; beta_m, beta_n: longitudinal and azimuthal roughness in
  // [0, 1]; alpha_deg: the scales' tilt in degrees; tangent: the fibre's
  // direction in the shading frame.
  HairBSDF(float h, float eta, const Spectrum& sigma_a, float beta_m, float beta_n, float alpha_deg, const Vec3& tangent)
      : h_(glm::clamp(h, -1.f, 1.f)), eta_(eta), sigma_a_(sigma_a) {
    Vec3 x(tangent.x, tangent.y, 0.f);
    float l = glm::length(x);
    x_ = l > 0.f ? x / l : Vec3(1.f, 0.f, 0.f);
    y_ = Vec3(-x_.y, x_.x, 0.f);
    gamma_o_ = std::asin(h_);
    // Roughness to lobe variances and the logistic's scale (Chiang et al.
    // 2016, eq. 7 and 8).
    v_[0] = sqr(0.726f * beta_m + 0.812f * sqr(beta_m) + 3.7f * std::pow(beta_m, 20.f));
    v_[1] = 0.25f * v_[0];
    v_[2] = 4.f * v_[0];
    v_[3] = v_[2];
    s_ = 0.626657069f * (0.265f * beta_n + 1.194f * sqr(beta_n) + 5.372f * std::pow(beta_n, 22.f));  // sqrt(pi/8)
    // sin and cos of 2^k alpha, k = 0, 1, 2: the R, TT and TRT tilts.
    sin2k_alpha_[0] = std::sin(glm::radians(alpha_deg));
    cos2k_alpha_[0] = safe_sqrt(1.f - sqr(sin2k_alpha_[0]));
    for (int i = 1; i < 3; ++i) {
      sin2k_alpha_[i] = 2.f * cos2k_alpha_[i - 1] * sin2k_alpha_[i - 1];
      cos2k_alpha_[i] = sqr(cos2k_alpha_[i - 1]) - sqr(sin2k_alpha_[i - 1]);
    }
  }

  bool is_specular() const { return false; }

  // Radiance: S(wo, wi), the fibre's scattering from wi towards wo. The
  // fibre is seen across its width by the ray that found it, so a vertex
  // found from the light side weighs the camera-side direction by the
  // fibre's width as the light saw it: importance carries the adjoint,
  // S(wi, wo) times the ratio of the two directions' cosines to the fibre's
  // normal plane. Without it bdpt was up to 20% brighter than the path
  // tracer on a hair ball (docs/materials.md, hair).
  Spectrum f(const Vec3& wo, const Vec3& wi, TransportMode mode) const {
    Spectrum s;
    if (mode == TransportMode::Radiance) {
      s = scattering(angles(wo), angles(wi));
    } else {
      const Angles o = angles(wo), i = angles(wi);
      s = o.cos_theta > 0.f ? scattering(i, o) * (i.cos_theta / o.cos_theta) : Spectrum(0.f);
    }
    float c = std::fabs(wi.z);
    return c > 0.f ? s / c : s;
  }

  float pdf(const Vec3& wo, const Vec3& wi, TransportMode, Lobes = Lobes::All) const {
    const Angles o = angles(wo), i = angles(wi);
    const Internal in = internal(o);
    const std::array<float, kPMax + 1> w = term_weights(o.cos_theta, in.T);
    const float phi = i.phi - o.phi;
    float sum = 0.f;
    for (int p = 0; p < kPMax; ++p) {
      const Angles t = tilted(o, p);
      sum += mp(i.cos_theta, t.cos_theta, i.sin_theta, t.sin_theta, v_[p]) * w[size_t(p)] * np(phi, p, in.gamma_t);
    }
    sum += mp(i.cos_theta, o.cos_theta, i.sin_theta, o.sin_theta, v_[kPMax]) * w[kPMax] * kInv2Pi;
    return sum;
  }

  // Picks a term p by its share of the attenuation, then theta_i from Mp
  // (d'Eon et al. 2011's sampling of the spherical Gaussian around the
  // tilted mirror direction), then phi_i from Np.
  std::optional<BSDFSample> sample_f(const Vec3& wo, float uc, Vec2 u, TransportMode mode,
                                     Lobes = Lobes::All) const {
    const Angles o = angles(wo);
    const Internal in = internal(o);
    const std::array<float, kPMax + 1> w = term_weights(o.cos_theta, in.T);
    int p = 0;
    while (p < kPMax && uc >= w[size_t(p)]) uc -= w[size_t(p++)];
    if (!(w[size_t(p)] > 0.f)) return std::nullopt;
    uc = min_num(uc / w[size_t(p)], 0x1.fffffep-1f);
    const Angles t = p < kPMax ? tilted(o, p) : o;
    const float u0 = max_num(u.x, 1e-5f);
    const float cos_theta = 1.f + v_[p] * std::log(u0 + (1.f - u0) * std::exp(-2.f / v_[p]));
    const float sin_theta = safe_sqrt(1.f - sqr(cos_theta));
    const float sin_ti = -cos_theta * t.sin_theta + sin_theta * std::cos(2.f * kPi * u.y) * t.cos_theta;
    const float cos_ti = safe_sqrt(1.f - sqr(sin_ti));
    const float dphi = p < kPMax ? exit_azimuth(p, in.gamma_t) + sample_trimmed_logistic(uc) : 2.f * kPi * uc;
    const float phi_i = o.phi + dphi;
    const Vec3 wi = x_ * sin_ti + y_ * (cos_ti * std::cos(phi_i)) + Vec3(0.f, 0.f, cos_ti * std::sin(phi_i));
    BSDFSample s;
    s.wi = wi;
    s.pdf = pdf(wo, wi, mode);
    if (!(s.pdf > 0.f)) return std::nullopt;
    s.f = f(wo, wi, mode);
    s.transmission = wi.z * wo.z < 0.f;
    return s;
  }

 private:
  struct Angles {
    float sin_theta, cos_theta, phi;
  };
  // What the path inside the fibre sees: the refracted azimuthal angle and
  // the transmittance of one crossing.
  struct Internal {
    float gamma_t;
    Spectrum T;
  };

  // S: the sum of the terms for light leaving towards o from i, with h and
  // the internal path taken for o.
  Spectrum scattering(const Angles& o, const Angles& i) const {
    const Internal in = internal(o);
    const std::array<Spectrum, kPMax + 1> ap = attenuation(o.cos_theta, in.T);
    const float phi = i.phi - o.phi;
    Spectrum sum(0.f);
    for (int p = 0; p < kPMax; ++p) {
      const Angles t = tilted(o, p);
      sum += mp(i.cos_theta, t.cos_theta, i.sin_theta, t.sin_theta, v_[p]) * ap[size_t(p)] * np(phi, p, in.gamma_t);
    }
    return sum + mp(i.cos_theta, o.cos_theta, i.sin_theta, o.sin_theta, v_[kPMax]) * ap[kPMax] * kInv2Pi;
  }

  Angles angles(const Vec3& w) const {
    const float sx = glm::clamp(glm::dot(w, x_), -1.f, 1.f), yy = glm::dot(w, y_);
    return {sx, safe_sqrt(1.f - sx * sx), std::atan2(w.z, yy)};
  }

  Internal internal(const Angles& o) const {
    const float sin_tt = o.sin_theta / eta_, cos_tt = safe_sqrt(1.f - sqr(sin_tt));
    // The modified index in the plane perpendicular to the fibre (Bravais).
    const float etap = o.cos_theta > 0.f ? safe_sqrt(sqr(eta_) - sqr(o.sin_theta)) / o.cos_theta : 1e30f;
    const float sin_gt = glm::clamp(h_ / etap, -1.f, 1.f), cos_gt = safe_sqrt(1.f - sqr(sin_gt));
    const float len = cos_tt > 0.f ? 2.f * cos_gt / cos_tt : 1e30f;
    return {std::asin(sin_gt), exp(-sigma_a_ * len)};
  }

  // The direction a term's lobe is centred on: theta_o tilted by -2 alpha
  // (R), alpha (TT), 4 alpha (TRT).
  Angles tilted(const Angles& o, int p) const {
    const int k = p == 0 ? 1 : p == 1 ? 0 : 2;
    const float sg = p == 0 ? -1.f : 1.f;
    return {o.sin_theta * cos2k_alpha_[k] + sg * o.cos_theta * sin2k_alpha_[k],
            std::fabs(o.cos_theta * cos2k_alpha_[k] - sg * o.sin_theta * sin2k_alpha_[k]), o.phi};
  }

  std::array<Spectrum, kPMax + 1> attenuation(float cos_theta_o, const Spectrum& T) const {
    const float cos_gamma_o = safe_sqrt(1.f - sqr(h_));
    const float fr = fr_dielectric(cos_theta_o * cos_gamma_o, eta_);
    std::array<Spectrum, kPMax + 1> ap;
    ap[0] = Spectrum(fr);
    ap[1] = sqr(1.f - fr) * T;
    ap[2] = ap[1] * T * fr;
    ap[3] = ap[2] * fr * T / max(Spectrum(1.f) - T * fr, Spectrum(1e-12f));
    return ap;
  }

  std::array<float, kPMax + 1> term_weights(float cos_theta_o, const Spectrum& T) const {
    const std::array<Spectrum, kPMax + 1> ap = attenuation(cos_theta_o, T);
    std::array<float, kPMax + 1> w;
    float total = 0.f;
    for (int p = 0; p <= kPMax; ++p) total += (w[size_t(p)] = average(ap[size_t(p)]));
    for (float& x : w) x = total > 0.f ? x / total : 0.f;
    return w;
  }

  // The longitudinal lobe (d'Eon et al. 2011), in log space for narrow
  // lobes where I0 and sinh overflow. I0 is evaluated to single precision
  // (pbrt-v4's shorter series is up to 2% low near its switch to the
  // asymptotic form, which makes the lobe integrate to 0.998 and its
  // density disagree with its sampling).
  static float mp(float cos_ti, float cos_to, float sin_ti, float sin_to, float v) {
    const double a = double(cos_ti) * cos_to / v, b = double(sin_ti) * sin_to / v;
    if (v <= 0.1f) return float(std::exp(log_i0(a) - b - 1.0 / v + std::log(1.0 / v)));
    return float(std::exp(log_i0(a) - b) / (std::sinh(1.0 / v) * 2.0 * v));
  }
  // log of the modified Bessel function of the first kind, order 0: its
  // power series, and for large x its asymptotic expansion
  // (Abramowitz & Stegun 9.6.12 and 9.7.1).
  static double log_i0(double x) {
    x = std::fabs(x);
    if (x > 15.0) {
      const double r = 1.0 / (8.0 * x);
      return x - 0.5 * std::log(2.0 * kPi * x) + std::log1p(r * (1.0 + r * (4.5 + r * 37.5)));
    }
    const double q = 0.25 * x * x;
    double term = 1.0, sum = 1.0;
    for (int k = 1; k < 60 && term > 1e-9 * sum; ++k) {
      term *= q / (double(k) * k);
      sum += term;
    }
    return std::log(sum);
  }

  float exit_azimuth(int p, float gamma_t) const {
    return 2.f * float(p) * gamma_t - 2.f * gamma_o_ + float(p) * kPi;
  }
  float np(float phi, int p, float gamma_t) const {
    float d = phi - exit_azimuth(p, gamma_t);
    d = std::remainder(d, 2.f * kPi);  // into [-pi, pi]
    return trimmed_logistic(d);
  }
  float logistic_cdf(float x) const { return 1.f / (1.f + std::exp(-x / s_)); }
  // The logistic of scale s restricted to [-pi, pi] and renormalised.
  float trimmed_logistic(float x) const {
    const float e = std::exp(-std::fabs(x) / s_);
    return e / (s_ * sqr(1.f + e)) / (logistic_cdf(kPi) - logistic_cdf(-kPi));
  }
  float sample_trimmed_logistic(float u) const {
    const float lo = logistic_cdf(-kPi), k = logistic_cdf(kPi) - lo;
    const float x = -s_ * std::log(1.f / (u * k + lo) - 1.f);
    return glm::clamp(x, -kPi, kPi);
  }

  float h_, eta_;
  Spectrum sigma_a_;
  Vec3 x_, y_;  // the fibre's frame in the shading frame (z shared)
  float gamma_o_;
  float v_[kPMax + 1];
  float s_;
  float sin2k_alpha_[3], cos2k_alpha_[3];
};

}  // namespace lantern
