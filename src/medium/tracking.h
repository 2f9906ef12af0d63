// Null-collision tracking: distance sampling and transmittance through a
// medium whose extinction is known only point by point, under a majorant
// that bounds it. Delta tracking: Woodcock et al. 1965; ratio tracking:
// Novak, Selle & Jarosz 2014; the null-collision integral with collision
// probabilities of one's choosing: Galtier et al. 2013, Miller, Georgiev &
// Jarosz 2019.
//
// Along a stretch with a grey majorant sigma_bar >= sigma_t,c for every
// channel c, tentative collisions come at exponential steps of rate
// sigma_bar. At each, the coefficients are looked up; the collision is real
// with probability q = mean_c sigma_t,c / sigma_bar, and null otherwise.
// The per-channel weights that keep every channel's estimate unbiased are
//   real: sigma_s,c / (sigma_bar q)        = sigma_s,c / mean sigma_t
//   null: sigma_n,c / (sigma_bar (1 - q))  = sigma_n,c / mean sigma_n
// with sigma_n,c = sigma_bar - sigma_t,c. In a grey medium they are the
// analog ones: the albedo at a real collision, 1 at a null one. In a
// coloured one each null factor is at most 3.
#pragma once

#include <cmath>

#include "math/common.h"
#include "math/rng.h"

namespace lantern::tracking {

// A stretch of this many tentative collisions ends as absorbed (delta
// tracking) or blocked (ratio tracking): a bound, so that an absurd
// majorant over a long stretch cannot hang a render.
constexpr int kMaxSteps = 1 << 20;

// Each channel is the one a collision is decided by with this probability
// (the mean of the channels' extinctions).
constexpr float kChannelProbability = 1.f / float(kSpectrumSamples);

struct Track {
  float t = kInfinity;  // the real collision's distance; infinity: passed the stretch
  Spectrum weight{1.f};  // per channel, the product of the collision weights
  Spectrum sigma_a{0.f}, sigma_s{0.f};  // at the real collision
  bool saturated = false;          // ended by kMaxSteps
  bool real() const { return t < kInfinity; }
};

inline float exponential_step(float u, float rate) { return -std::log1p(-min_num(u, 0x1.fffffep-1f)) / rate; }

// Delta tracking over [0, L]; `at(t, &sigma_a, &sigma_s)` gives the
// coefficients at distance t. u: the first step's uniform number; rng
// gives the rest.
template <class Coefficients>
Track delta_track(float L, float sigma_bar, float u, RandomStream& rng, Coefficients&& at) {
  Track r;
  if (!(sigma_bar > 0.f)) return r;
  float t = 0.f;
  for (int step = 0; step < kMaxSteps; ++step) {
    t += exponential_step(u, sigma_bar);
    if (!(t < L)) return r;
    Spectrum a, s;
    at(t, &a, &s);
    const Spectrum st = a + s;
    const float mean_t = sum(st) * kChannelProbability;
    if (rng.get1d() * sigma_bar < mean_t) {
      r.t = t;
      r.sigma_a = a;
      r.sigma_s = s;
      r.weight *= s / mean_t;
      return r;
    }
    const Spectrum sn = max(Spectrum(sigma_bar) - st, Spectrum(0.f));
    r.weight *= sn / (sum(sn) * kChannelProbability);
    u = rng.get1d();
  }
  r.saturated = true;
  r.weight = Spectrum(0.f);
  return r;
}

// Ratio tracking over [0, L]: an unbiased estimate of the transmittance
// per channel. Once every channel is below 0.1 the estimate goes on with
// probability 10 max T, divided by it (Russian roulette), so deep
// stretches end early.
template <class Coefficients>
Spectrum ratio_track(float L, float sigma_bar, RandomStream& rng, Coefficients&& at) {
  Spectrum T(1.f);
  if (!(sigma_bar > 0.f)) return T;
  float t = 0.f;
  for (int step = 0; step < kMaxSteps; ++step) {
    t += exponential_step(rng.get1d(), sigma_bar);
    if (!(t < L)) return T;
    Spectrum a, s;
    at(t, &a, &s);
    T *= max(Spectrum(1.f) - (a + s) / sigma_bar, Spectrum(0.f));
    const float m = max_component(T);
    if (m < 0.1f) {
      if (!(rng.get1d() < 10.f * m)) return Spectrum(0.f);
      T /= 10.f * m;
    }
  }
  return Spectrum(0.f);
}

}  // namespace lantern::tracking
