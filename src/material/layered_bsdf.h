// A layered BSDF: a top interface over an opaque bottom, with an optional
// homogeneous medium of unit extinction between them, evaluated by random
// walks between the two interfaces. This is the model pbrt-v4 renders for
// coateddiffuse and coatedconductor (Pharr, Jakob & Humphreys, "Physically
// Based Rendering", 4th ed., sec. 14.3; after Guo, Hasan & Zhao 2018,
// "Position-free Monte Carlo simulation for arbitrary layered BSDFs").
//
//   f()        an unbiased estimate of the BSDF from n_samples walks with
//              next-event estimation towards wi at every vertex;
//   sample_f() one analog walk; its f / pdf ratio is the walk's weight, and
//              it is flagged pdf_is_proportional;
//   pdf()      a deterministic density for MIS only (see below).
//
// The walks draw their random numbers from a hash of their arguments, so
// f(wo, wi) is one fixed function for a render: images do not depend on
// threads or on the order of evaluation.
//
// MIS needs a density that every strategy evaluates identically for the
// same path. pbrt-v4's stochastic pdf estimate changes with the last bit of
// a direction, and the same path reached by two strategies has directions
// that differ in their last bits; so pdf() is instead a closed form: the
// coat's reflection lobe weighted by its Fresnel reflectance, plus a cosine
// lobe for light that went through the coat. Any such density gives an
// unbiased estimator as long as it is positive wherever the walk can go
// (Veach 1997, sec. 9.2): the weights of all strategies still sum to one.
//
// Two details differ from pbrt-v4's code, so that f() and sample_f() are
// unbiased estimates of one BSDF (the analog slab the tests simulate):
// - where the walk samples a direction that goes out through the coat, its
//   MIS partner is the density with which wis would have been drawn, over
//   the same inside directions (pbrt pairs it with the density of wi given
//   the inside direction, a different measure: f comes out up to 8% high);
// - f() gathers light leaving by step max_depth - 1 at the latest, as
//   sample_f() can (pbrt's f() admits walks one step longer).
//
// Only two-sided layers over an opaque bottom are modelled (what pbrt-v4's
// coated materials are): wo below the surface is mirrored above it, and a
// pair of directions on opposite sides has f = 0.
#pragma once

#include <bit>

#include "material/bsdf_common.h"
#include "material/fresnel.h"
#include "math/rng.h"
#include "math/sampling.h"
#include "medium/henyey_greenstein.h"

namespace lantern {

// Random numbers for one walk, from a hash of the walk's arguments.
class HashedRng {
 public:
  explicit HashedRng(std::initializer_list<float> key) {
    uint64_t h = 0x6A09E667F3BCC908ULL;
    for (float v : key) h = mix64(h ^ std::bit_cast<uint32_t>(v));
    state_ = h;
  }
  float next() {
    state_ += 0x9E3779B97F4A7C15ULL;
    return bits_to_unit_float(mix64(state_));
  }
  Vec2 next2() {
    float a = next();
    return Vec2(a, next());
  }

 private:
  uint64_t state_;
};

template <class Top, class Bottom>
struct LayeredBSDF {
  Top top;
  Bottom bottom;
  float thickness;  // in units of the medium's mean free path
  Spectrum albedo;       // single-scattering albedo of the medium (0: none)
  float g;          // Henyey-Greenstein asymmetry of the medium
  int max_depth;    // scattering events a walk may have
  int n_samples;    // walks per evaluation of f

  // Only when every interaction inside is a mirror (a smooth coat over a
  // smooth conductor, nothing between): then f is 0 and every sample a delta.
  bool is_specular() const { return top.is_specular() && bottom.is_specular() && !has_medium(); }

  Spectrum f(Vec3 wo, Vec3 wi, TransportMode mode) const {
    if (wo.z < 0.f) {
      wo = -wo;
      wi = -wi;
    }
    if (!(wi.z > 0.f) || !(wo.z > 0.f)) return Spectrum(0.f);
    Spectrum sum = float(n_samples) * top.f(wo, wi, mode);  // reflection at the coat
    HashedRng r{wo.x, wo.y, wo.z, wi.x, wi.y, wi.z};
    for (int s = 0; s < n_samples; ++s) sum += walk_estimate(wo, wi, mode, r);
    return sum / float(n_samples);
  }

  std::optional<BSDFSample> sample_f(Vec3 wo, float uc, Vec2 u, TransportMode mode) const {
    const bool flip = wo.z < 0.f;
    if (flip) wo = -wo;
    auto bs = top.sample_f(wo, uc, u, mode);
    if (!valid(bs)) return std::nullopt;
    if (!bs->transmission) {  // reflected by the coat
      bs->pdf_is_proportional = !bs->specular;
      if (flip) bs->wi = -bs->wi;
      return bs;
    }
    HashedRng r{wo.x, wo.y, wo.z, uc, u.x, u.y};
    return walk_sample(*bs, mode, r, flip);
  }

  // The MIS density (see the header comment), in closed form.
  float pdf(Vec3 wo, Vec3 wi, TransportMode mode) const {
    if (wo.z < 0.f) {
      wo = -wo;
      wi = -wi;
    }
    if (!(wi.z > 0.f) || !(wo.z > 0.f) || is_specular()) return 0.f;
    float pc = fr_dielectric(wo.z, top.eta);
    float p = (1.f - pc) * cosine_hemisphere_pdf(wi.z);
    if (!top.is_specular()) p += pc * top.pdf(wo, wi, mode, Lobes::Reflection);
    return p;
  }

 private:
  static bool valid(const std::optional<BSDFSample>& bs) {
    return bs && bs->pdf > 0.f && !is_black(bs->f) && bs->wi.z != 0.f;
  }
  // Transmittance through a height difference dz along w.
  static float tr(float dz, const Vec3& w) {
    if (std::fabs(dz) <= std::numeric_limits<float>::min()) return 1.f;
    return std::exp(-std::fabs(dz / w.z));
  }
  bool has_medium() const { return !is_black(albedo); }
  // The density over inside directions w (travelling up) with which the
  // pre-sampled wis would have been drawn: the other strategy's density when
  // the walk itself samples w and then goes out through the coat to wi.
  float exit_pdf(const Vec3& wi, const Vec3& w, TransportMode mode) const {
    return top.pdf(wi, -w, adjoint(mode), Lobes::Transmission);
  }

  // One walk that enters through the coat along wo and gathers, at every
  // vertex, the light that leaves through the coat towards wi, each vertex
  // combining two strategies by MIS: the pre-sampled direction wis through
  // the coat, and the direction the walk samples next.
  Spectrum walk_estimate(const Vec3& wo, const Vec3& wi, TransportMode mode, HashedRng& r) const {
    float uc = r.next();
    auto wos = top.sample_f(wo, uc, r.next2(), mode, Lobes::Transmission);
    if (!valid(wos)) return Spectrum(0.f);
    uc = r.next();
    auto wis = top.sample_f(wi, uc, r.next2(), adjoint(mode), Lobes::Transmission);
    if (!valid(wis)) return Spectrum(0.f);
    const bool top_specular = top.is_specular();
    const Spectrum wis_weight = wis->f / wis->pdf;
    const HenyeyGreenstein phase{g};
    Spectrum sum(0.f);
    Spectrum beta = wos->f * (abs_cos_theta(wos->wi) / wos->pdf);
    float z = thickness;
    Vec3 w = wos->wi;
    // Light gathered at step d leaves at step d + 1; a sampled walk leaves
    // by step max_depth - 1 at the latest, and so must these.
    for (int depth = 0; depth + 1 < max_depth; ++depth) {
      if (depth > 3 && max_component(beta) < 0.25f) {  // Russian roulette
        float q = max_num(0.f, 1.f - max_component(beta));
        if (r.next() < q) break;
        beta /= 1.f - q;
      }
      if (!has_medium()) {
        z = z == thickness ? 0.f : thickness;
        beta *= tr(thickness, w);
      } else {
        float zp = w.z > 0.f ? z + sample_exponential(r.next(), 1.f / std::fabs(w.z))
                             : z - sample_exponential(r.next(), 1.f / std::fabs(w.z));
        if (zp == z) continue;
        if (0.f < zp && zp < thickness) {  // scattered inside the medium
          float wt = top_specular ? 1.f : power_heuristic(wis->pdf, phase.pdf(-w, -wis->wi));
          sum += beta * albedo * wis_weight * (phase.p(-w, -wis->wi) * wt * tr(zp - thickness, wis->wi));
          float ps_pdf;
          Vec3 wn = phase.sample(-w, r.next2(), &ps_pdf);
          if (!(ps_pdf > 0.f) || wn.z == 0.f) continue;
          beta *= albedo;  // p / pdf = 1: the phase function is sampled exactly
          w = wn;
          z = zp;
          if (w.z > 0.f && !top_specular) {
            Spectrum f_exit = top.f(-w, wi, mode);
            if (!is_black(f_exit)) {
              float wt2 = power_heuristic(ps_pdf, exit_pdf(wi, w, mode));
              sum += beta * f_exit * (tr(zp - thickness, w) * wt2);
            }
          }
          continue;
        }
        z = glm::clamp(zp, 0.f, thickness);
      }
      if (z == thickness) {  // back at the coat, from inside: reflect
        uc = r.next();
        auto bs = top.sample_f(-w, uc, r.next2(), mode, Lobes::Reflection);
        if (!valid(bs)) break;
        beta *= bs->f * (abs_cos_theta(bs->wi) / bs->pdf);
        w = bs->wi;
        continue;
      }
      // At the bottom: light from wis, then a new direction.
      if (!bottom.is_specular()) {
        float wt = top_specular ? 1.f : power_heuristic(wis->pdf, bottom.pdf(-w, -wis->wi, mode));
        sum += beta * bottom.f(-w, -wis->wi, mode) * wis_weight *
               (abs_cos_theta(wis->wi) * wt * tr(thickness, wis->wi));
      }
      uc = r.next();
      auto bs = bottom.sample_f(-w, uc, r.next2(), mode, Lobes::Reflection);
      if (!valid(bs)) break;
      beta *= bs->f * (abs_cos_theta(bs->wi) / bs->pdf);
      w = bs->wi;
      if (!top_specular) {
        Spectrum f_exit = top.f(-w, wi, mode);
        if (!is_black(f_exit)) {
          float wt = bottom.is_specular() ? 1.f : power_heuristic(bs->pdf, exit_pdf(wi, w, mode));
          sum += beta * f_exit * (tr(thickness, bs->wi) * wt);
        }
      }
    }
    return sum;
  }

  // Continues a sample that went through the coat along entry.wi until it
  // leaves through the coat again; f and pdf are products along the walk.
  std::optional<BSDFSample> walk_sample(const BSDFSample& entry, TransportMode mode, HashedRng& r, bool flip) const {
    const HenyeyGreenstein phase{g};
    Vec3 w = entry.wi;
    bool specular_path = entry.specular;
    // The walk's f / pdf, kept as one ratio: the products alone overflow
    // after a few bounces on a nearly smooth coat.
    Spectrum beta = entry.f * (abs_cos_theta(entry.wi) / entry.pdf);
    float z = thickness;
    for (int depth = 0; depth < max_depth; ++depth) {
      float rr_beta = max_component(beta);
      if (depth > 3 && rr_beta < 0.25f) {
        float q = max_num(0.f, 1.f - rr_beta);
        if (r.next() < q) return std::nullopt;
        beta /= 1.f - q;
      }
      if (w.z == 0.f) return std::nullopt;
      if (has_medium()) {
        float dz = sample_exponential(r.next(), 1.f / std::fabs(w.z));
        float zp = w.z > 0.f ? z + dz : z - dz;
        if (zp == z) return std::nullopt;
        if (0.f < zp && zp < thickness) {
          float ps_pdf;
          Vec3 wn = phase.sample(-w, r.next2(), &ps_pdf);
          if (!(ps_pdf > 0.f) || wn.z == 0.f) return std::nullopt;
          beta *= albedo;  // the phase function is sampled exactly
          specular_path = false;
          w = wn;
          z = zp;
          continue;
        }
        z = glm::clamp(zp, 0.f, thickness);
      } else {
        z = z == thickness ? 0.f : thickness;
        beta *= tr(thickness, w);
      }
      float uc = r.next();
      Vec2 u = r.next2();
      auto bs = z == 0.f ? bottom.sample_f(-w, uc, u, mode) : top.sample_f(-w, uc, u, mode);
      if (!valid(bs)) return std::nullopt;
      beta *= bs->f / bs->pdf;
      specular_path = specular_path && bs->specular;
      w = bs->wi;
      if (!is_finite(beta)) return std::nullopt;
      if (bs->transmission) {  // out through the coat
        BSDFSample out;
        out.f = beta;  // f cos / pdf is the walk's weight (without the last cosine, as for any sample)
        out.wi = flip ? -w : w;
        out.pdf = 1.f;
        out.specular = specular_path;
        out.pdf_is_proportional = !specular_path;
        return out;
      }
      beta *= abs_cos_theta(bs->wi);
    }
    return std::nullopt;
  }

  static float sample_exponential(float u, float a) { return -std::log1p(-u) / a; }
};

}  // namespace lantern
