// Colour and spectrum values: distinct from points and directions (Vec3),
// and distinct from each other.
//
// - `RGB` is colour as scene files give it: three coefficients in the
//   rendering colour space (linear sRGB), what textures, material and light
//   parameters and the output image hold.
// - `Spectrum` is what light transport carries: radiance, throughput, BSDF
//   values, transmittance and medium coefficients, with kSpectrumSamples
//   channels: a sample's values at its wavelengths in the spectral
//   renderer, R, G, B (and G again) in the RGB renderer. The two types meet
//   only where colour becomes spectrum (where a material, light or medium
//   reads its parameters) and where spectrum becomes colour (the film):
//   color/spectrum_conversion.h.
//
// Operations are hidden friends, found by argument-dependent lookup only, so
// `exp`, `sqrt`, `min`, `max` and `clamp` on floats are not shadowed.
#pragma once

#include <cmath>

#include "math/max_num.h"

namespace lantern {

inline constexpr int kSpectrumSamples = 4;  // as pbrt-v4 samples

// N coefficients with channel-wise arithmetic; Tag keeps colour and spectrum
// apart as types.
template <int N, class Tag>
class Channels {
 public:
  static constexpr int kSize = N;

  // Uninitialised, as a float is and as the glm vectors these replace
  // were: no code relies on zeroes it did not write.
  Channels() = default;
  constexpr explicit Channels(float v) {
    for (int i = 0; i < N; ++i) c_[i] = v;
  }
  constexpr Channels(float a, float b, float d) requires(N == 3) : c_{a, b, d} {}
  constexpr Channels(float a, float b, float d, float e) requires(N == 4) : c_{a, b, d, e} {}

  constexpr float& operator[](int i) { return c_[i]; }
  constexpr float operator[](int i) const { return c_[i]; }
  constexpr const float* data() const { return c_; }
  constexpr float* data() { return c_; }

#define LANTERN_CHANNEL_OP(op)                                                                \
  constexpr Channels& operator op##=(const Channels& o) {                                     \
    for (int i = 0; i < N; ++i) c_[i] op## = o.c_[i];                                         \
    return *this;                                                                             \
  }                                                                                           \
  constexpr Channels& operator op##=(float s) {                                               \
    for (int i = 0; i < N; ++i) c_[i] op## = s;                                               \
    return *this;                                                                             \
  }                                                                                           \
  friend constexpr Channels operator op(Channels a, const Channels& b) { return a op## = b; } \
  friend constexpr Channels operator op(Channels a, float s) { return a op## = s; }           \
  friend constexpr Channels operator op(float s, const Channels& b) {                         \
    Channels r;                                                                               \
    for (int i = 0; i < N; ++i) r.c_[i] = s op b.c_[i];                                       \
    return r;                                                                                 \
  }
  LANTERN_CHANNEL_OP(+)
  LANTERN_CHANNEL_OP(-)
  LANTERN_CHANNEL_OP(*)
  LANTERN_CHANNEL_OP(/)
#undef LANTERN_CHANNEL_OP

  friend constexpr Channels operator-(const Channels& a) {
    return map(a, [](float x) { return -x; });
  }
  friend constexpr bool operator==(const Channels& a, const Channels& b) {
    for (int i = 0; i < N; ++i)
      if (a.c_[i] != b.c_[i]) return false;
    return true;
  }

  // Channel-wise functions.
  friend Channels exp(const Channels& a) {
    return map(a, [](float x) { return std::exp(x); });
  }
  friend Channels log(const Channels& a) {
    return map(a, [](float x) { return std::log(x); });
  }
  friend Channels sqrt(const Channels& a) {
    return map(a, [](float x) { return std::sqrt(x); });
  }
  friend Channels abs(const Channels& a) {
    return map(a, [](float x) { return std::fabs(x); });
  }
  friend Channels pow(const Channels& a, float e) {
    return map(a, [e](float x) { return std::pow(x, e); });
  }
  friend constexpr Channels min(const Channels& a, const Channels& b) {
    Channels r;
    for (int i = 0; i < N; ++i) r.c_[i] = b.c_[i] < a.c_[i] ? b.c_[i] : a.c_[i];
    return r;
  }
  friend constexpr Channels max(const Channels& a, const Channels& b) {
    Channels r;
    for (int i = 0; i < N; ++i) r.c_[i] = a.c_[i] < b.c_[i] ? b.c_[i] : a.c_[i];
    return r;
  }
  friend constexpr Channels clamp(const Channels& a, float lo, float hi) {
    return min(max(a, Channels(lo)), Channels(hi));
  }
  friend constexpr Channels clamp(const Channels& a, const Channels& lo, const Channels& hi) {
    return min(max(a, lo), hi);
  }
  // (1 - t) a + t b (as glm::mix), by one weight or channel-wise.
  friend constexpr Channels mix(const Channels& a, const Channels& b, float t) { return a * (1.f - t) + b * t; }
  friend constexpr Channels mix(const Channels& a, const Channels& b, const Channels& t) {
    return a * (Channels(1.f) - t) + b * t;
  }

  // Reductions.
  friend constexpr float max_component(const Channels& a) {
    float m = a.c_[0];
    for (int i = 1; i < N; ++i) m = max_num(m, a.c_[i]);
    return m;
  }
  friend constexpr float min_component(const Channels& a) {
    float m = a.c_[0];
    for (int i = 1; i < N; ++i) m = min_num(m, a.c_[i]);
    return m;
  }
  friend constexpr float sum(const Channels& a) {
    float s = a.c_[0];
    for (int i = 1; i < N; ++i) s += a.c_[i];
    return s;
  }
  friend constexpr float average(const Channels& a) { return sum(a) / float(N); }
  friend constexpr bool is_black(const Channels& a) {
    for (int i = 0; i < N; ++i)
      if (a.c_[i] != 0.f) return false;
    return true;
  }
  friend bool is_finite(const Channels& a) {
    for (int i = 0; i < N; ++i)
      if (!std::isfinite(a.c_[i])) return false;
    return true;
  }

 private:
  template <class F>
  static constexpr Channels map(const Channels& a, F f) {
    Channels r;
    for (int i = 0; i < N; ++i) r.c_[i] = f(a.c_[i]);
    return r;
  }

  float c_[N];
};

struct RGBTag {};
struct SpectrumTag {};
using RGB = Channels<3, RGBTag>;
using Spectrum = Channels<kSpectrumSamples, SpectrumTag>;

// Relative luminance Y of linear sRGB (ITU-R BT.709 primaries, D65 white).
constexpr float luminance(const RGB& c) { return 0.2126f * c[0] + 0.7152f * c[1] + 0.0722f * c[2]; }

}  // namespace lantern
