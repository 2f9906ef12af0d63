// Rays through participating media, in batches. A ray of a subpath is
// followed from its vertex through every medium it crosses ("interface"
// boundaries are crossed and the ray traced on, the rays of a batch that
// cross together traced together) until distance sampling picks a
// scattering point, or it reaches a surface, or it escapes. Shadow and
// connection rays are followed the same way to their end, collecting the
// transmittance; any other surface blocks them.
//
// Distance sampling with Spectrum coefficients (docs/media.md): each ray picks
// one channel c uniformly and samples the optical depth of that channel,
// tau_c ~ Exp(1). The density of the point reached is then the mixture
//   p(t) = 1/3 sum_c sigma_t,c(t) T_c(t)      (scattering at t)
//   P    = 1/3 sum_c T_c(d)                    (passing the whole segment)
// which is positive wherever any channel can scatter, so the estimator
// T sigma_s / p (each channel at most 3 sigma_s / sigma_t) is unbiased and
// bounded, and bidirectional MIS sees one density per vertex.
#pragma once

#include <vector>

#include "accel/ray_stream.h"
#include "integrator/guided_distance.h"
#include "scene/scene.h"

namespace lantern {

enum class SegmentEnd : uint8_t { Surface, Scatter, Escaped, Absorbed };

// The mixture densities of a segment with transmittance T, ending at a
// medium point of extinction sigma_t (zero: a surface or infinity): each
// channel chosen with probability 1 / kSpectrumSamples.
inline float mixture_density(const Spectrum& sigma_t, const Spectrum& T) {
  constexpr float kChannelProbability = 1.f / float(kSpectrumSamples);
  return is_black(sigma_t) ? sum(T) * kChannelProbability : sum(sigma_t * T) * kChannelProbability;
}

// Per ray of a batch: where its segment ended, and what it contributes.
struct SegmentEnds {
  std::vector<SegmentEnd> end;
  std::vector<Vec3> p;              // the scattering point
  std::vector<Spectrum> weight;          // the segment's throughput factor, T sigma_s / p or T / P
  std::vector<Spectrum> T;               // its transmittance, as the MIS densities see it
  std::vector<float> fwd_density;   // p or P of the end reached (for MIS)
  std::vector<MediumHandle> medium;  // the medium the segment ends in
  std::vector<Spectrum> sigma_t;          // the extinction at the scattering point
  // Scenes with emissive media only: at a scattering point, T sigma_a Le / p
  // (the segment's emission estimate, per unit of the throughput before it).
  std::vector<Spectrum> emission;

  void resize(uint32_t n) {
    sigma_t.resize(n);
    end.resize(n);
    p.resize(n);
    weight.resize(n);
    T.resize(n);
    fwd_density.resize(n);
    medium.resize(n);
  }
  size_t memory_bytes() const {
    return vector_bytes(end) + vector_bytes(p) + vector_bytes(weight) + vector_bytes(T) + vector_bytes(fwd_density) +
           vector_bytes(medium) + vector_bytes(sigma_t) + vector_bytes(emission);
  }
};

// Scratch for the rays that cross boundaries, reused batch after batch.
struct CrossingScratch {
  RayBatch rays;
  RayBatch continued;
  std::vector<uint32_t> owner, next;  // the ray of the caller's batch each one continues
  std::vector<MediumHandle> medium;
  std::vector<float> tau;
  std::vector<uint8_t> channel;
  std::vector<Spectrum> depth;  // optical depth so far, per channel
  // Tracked media (scenes with them only): the weights so far, and the
  // proxy's depth so far.
  std::vector<Spectrum> tracked_weight, tracked_depth;
  DistanceGuide distance_guide;  // guided distances (integrator/guided_distance.h)
  size_t memory_bytes() const {
    return rays.memory_bytes() + continued.memory_bytes() + vector_bytes(owner) + vector_bytes(next) + vector_bytes(medium) + vector_bytes(tau) +
           vector_bytes(channel) + vector_bytes(depth) + vector_bytes(tracked_weight) + vector_bytes(tracked_depth);
  }
};

// Follows each ray i of `rays` (already intersected) that starts in
// medium[i], sampling its distance with the uniform number u[i], its
// coefficients at its sample's wavelengths lambda[i]. Rays that end on a
// surface keep that hit in `rays` (their origin moved to the last boundary
// crossed, their direction unchanged). With a scattered radiance field,
// the points where rays scatter in homogeneous media are guided by what it
// learnt (integrator/guided_distance.h); fwd_density stays free flight's.
void find_segment_ends(const Scene& scene, RayStream& stream, RayKind kind, RayBatch& rays,
                       const std::vector<MediumHandle>& medium, const std::vector<float>& u,
                       const std::vector<SampledWavelengths>& lambda, SegmentEnds& out, CrossingScratch& scratch,
                       const ScatterField* distance_guide = nullptr);

// The transmittance of each shadow ray of `rays` (origin, direction and
// t_max set, not yet traced) that starts in medium[i]: zero when a surface
// blocks it. Blocked rays are also marked occluded in `rays`. T is the
// estimate to weight the contribution by; T_mis the transmittance the MIS
// densities use (the same but where the ray crosses tracked media).
// Afterwards scratch.medium[i] is the medium ray i ends in (emissive
// media: a light sample counts only if it lies in its medium). lambda[i]:
// ray i's wavelengths.
void trace_transmittance(const Scene& scene, RayStream& stream, RayBatch& rays, const std::vector<MediumHandle>& medium,
                         const std::vector<SampledWavelengths>& lambda, std::vector<Spectrum>& T,
                         std::vector<Spectrum>& T_mis, CrossingScratch& scratch);

// The medium each point p[i] lies in, found along a ray from it to
// `known`, a point in medium `known_medium`: the side facing p[i] of the
// first boundary (of any material) between media that the ray meets, else
// known_medium. Surfaces that separate nothing are passed through.
// time[i]: p[i]'s time in the shutter (moving boundaries are where they
// are then).
void locate_media(const Scene& scene, RayStream& stream, const std::vector<Vec3>& p, const std::vector<float>& time,
                  const Vec3& known,
                  MediumHandle known_medium, std::vector<MediumHandle>& out, CrossingScratch& scratch);

// The medium a ray leaving a surface hit of geometry `geom` along w
// travels in, given the medium the hit was reached in.
inline MediumHandle medium_after(const Scene& scene, uint32_t geom, const Vec3& ng, const Vec3& w, MediumHandle current) {
  return scene.shapes.geometries[geom].media.after(ng, w, current);
}

}  // namespace lantern
