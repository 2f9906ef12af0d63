// Emission sampling (pbrt's Sample_Le / PDF_Le): where light subpaths start,
// and the densities bidirectional MIS needs to compare a light subpath's
// first vertex and direction against the other strategies.
#pragma once

#include <optional>

#include "light/lights.h"

namespace lantern {

struct EmissionSample {
  Vec3 p{0.f};          // origin: on the light, or on a disk outside the scene for lights at infinity
  Vec3 n{0.f};          // surface normal of an area light; zero otherwise
  Vec2 uv{0.f};         // surface coordinates of an area light's point
  Vec3 d{0.f};          // unit direction of emission
  Spectrum Le{0.f};     // radiance (area, infinite, distant) or intensity (point, spot) along d
  float pdf_pos = 0.f;  // area density of p times the selection pmf (delta position: the pmf)
  float pdf_dir = 0.f;  // solid-angle density of d (delta direction: 1)
  float error_scale = 0.f;
  uint32_t light = 0;  // index into LightPools::all
  bool delta_pos = false, delta_dir = false, infinite = false;
  // A point of an emissive medium (n zero): Le is 1, to be multiplied by
  // sigma_a Le there, and pdf_pos is per unit volume.
  bool volume = false;
};

// Chooses a light by `choice` (over LightPools::all: LightPools::selection
// chooses by power, as pbrt-v4's light subpaths do), a point on it and a
// direction leaving it; Le at the wavelengths l. u_pos.x makes the choice
// and, rescaled, places the point; u_select stands in for it after an
// unlikely choice (light_choice.h).
std::optional<EmissionSample> sample_le(const LightPools& lights, const ShapePools& shapes, const TexturePools& tex,
                                        const Distribution1D& choice, LazyNumber u_select, Vec2 u_pos, Vec2 u_dir,
                                        const SampledWavelengths& l, float u_volume = 0.5f);

// Turns an area light's emission sample es towards unit direction d (drawn
// by another technique, as guided light subpaths do): its radiance and the
// density sample_le would have given d. False for other kinds of sample.
bool redirect_area_emission(const LightPools& lights, const TexturePools& tex, EmissionSample& es, const Vec3& d,
                            const SampledWavelengths& l);

// Emission density (pos incl. the selection pmf, times dir) with which
// sample_le would start at p_light with normal n_light and leave in w.
// For lights at infinity, w is the direction the light travels.
float emission_pdf(const LightPools& lights, const ShapePools& shapes, const TexturePools& tex,
                   const Distribution1D& choice, uint32_t light, const Vec3& p_light, const Vec3& n_light,
                   const Vec3& w);
// Same for the area light hit by a ray: area_index indexes LightPools::area.
float area_emission_pdf(const LightPools& lights, const ShapePools& shapes, const Distribution1D& choice,
                        uint32_t area_index, const Vec3& p_light, const Vec3& n_light, const Vec3& w);
// Emission density (choice pmf included) with which a light subpath leaves
// infinite light `index` (into LightPools::infinite) along -w_to_light.
float infinite_emission_pdf(const LightPools& lights, const TexturePools& tex, const Distribution1D& choice,
                            uint32_t index, const Vec3& w_to_light);

// Radiance or intensity a light with finite position emits from (p, n) in
// w, at the wavelengths l.
Spectrum emitted(const LightPools& lights, const TexturePools& tex, uint32_t light, const Vec3& n, Vec2 uv, const Vec3& w,
                 const SampledWavelengths& l);

// Area density (times the pmf) with which sample_light picks p_light when
// called from p with normal n: next-event estimation's density of a light
// vertex.
float area_light_direct_pdf_area(const LightPools& lights, const ShapePools& shapes, const LightSampler& sampler,
                                 uint32_t area_index, const Vec3& p, const Vec3& n, const Vec3& p_light,
                                 const Vec3& n_light);

// Next-event estimation's density of the point a light subpath started
// from, as the first vertex it reaches would have sampled it (the light
// subpath's MIS start, Georgiev 2012's dVCM of the light's vertex). For
// lights at infinity without a portal it does not depend on that vertex:
// emission_direct_pdf_fixed gives it (the pmf, times the direction's
// density for an environment); for every other light it returns -1, and
// emission_direct_pdf_from gives it for the vertex p (shading normal ns,
// zero in a medium): per unit area on an area light of normal n_light at
// p_light, per unit volume in a volume light, the pmf for a delta
// position, and a portal light's density through its window.
float emission_direct_pdf_fixed(const LightPools& lights, const LightSampler& sampler, const EmissionSample& es);
float emission_direct_pdf_from(const LightPools& lights, const ShapePools& shapes, const TexturePools& tex,
                               const LightSampler& sampler, uint32_t light, const Vec3& n_light, const Vec3& p,
                               const Vec3& ns, const Vec3& p_light);

}  // namespace lantern
