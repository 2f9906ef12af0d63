// Emitter component pools, one per light kind, and the power distribution
// that selects among all of them.
#pragma once

#include <glm/mat3x3.hpp>
#include <optional>
#include <vector>

#include "color/spectrum_conversion.h"
#include "light/intensity_profile.h"
#include "light/portal.h"
#include "light/volume_light.h"
#include "math/distribution.h"
#include "math/equal_area.h"
#include "math/frame.h"
#include "math/lazy_number.h"
#include "medium/medium.h"
#include "texture/texture.h"

namespace lantern {

struct ShapePools;
struct SurfacePoint;
class LightSampler;  // light/light_sampler.h

enum class LightKind : uint8_t { Area, Point, Spot, Distant, Infinite, Volume };

struct AreaLight {  // one per emissive triangle or sphere
  uint32_t geometry;
  uint32_t primitive;
  RGB L;
  bool two_sided;
  float area;
  int32_t image = -1;  // pbrt-v4's "filename": L scales this image, looked up by (u, v)
  int32_t spectrum = -1;  // L given as a spectrum (light_spectrum below)
};
struct PointLight {
  Vec3 p;
  RGB I;
  int32_t profile = -1;  // goniometric and projection lights: index into LightPools::profiles
  MediumHandle medium;   // where its light starts
  int32_t spectrum = -1;  // I given as a spectrum (light_spectrum below)
};
struct SpotLight {
  Vec3 p;
  Frame frame;  // n = the cone's axis
  RGB I;
  float cos_falloff_start, cos_falloff_end;
  MediumHandle medium;
  int32_t spectrum = -1;  // I given as a spectrum (light_spectrum below)
};
struct DistantLight {
  Vec3 w;  // unit direction towards the light
  RGB L;
  int32_t spectrum = -1;  // L given as a spectrum (light_spectrum below)
};
struct InfiniteLight {
  RGB scale{1.f};
  glm::mat3 world_from_light{1.f}, light_from_world{1.f};
  int32_t image = -1;       // -1: constant radiance `scale`
  bool equal_area = true;   // pbrt-v4 octahedral equal-area map; else lat-long
  Distribution2D distribution;
  int32_t portal = -1;      // pbrt-v4's "portal": index into LightPools::portals, which then holds the map
  int32_t spectrum = -1;    // a constant L given as a spectrum (light_spectrum below)
};

// A light's emission at the wavelengths l from its colour c; `spectrum`
// indexes tex.spectra for a light given as a spectrum (emitted_spectrum,
// color/densely_sampled_spectrum.h).
inline Spectrum light_spectrum(const RGB& c, int32_t spectrum, const TexturePools& tex, const SampledWavelengths& l) {
  return emitted_spectrum(c, spectrum < 0 ? nullptr : &tex.spectra[size_t(spectrum)], l);
}

struct LightRef {
  LightKind kind;
  uint32_t index;
};

struct LightPools {
  std::vector<AreaLight> area;
  std::vector<PointLight> point;
  std::vector<SpotLight> spot;
  std::vector<DistantLight> distant;
  std::vector<InfiniteLight> infinite;
  std::vector<IntensityProfile> profiles;
  std::vector<PortalMap> portals;
  std::vector<VolumeLight> volume;  // emissive media (light/volume_light.h)

  std::vector<LightRef> all;        // what the selection distribution indexes
  std::vector<uint32_t> area_to_all;
  std::vector<uint32_t> infinite_to_all;
  std::vector<uint32_t> volume_to_all;
  // By power: how light subpaths choose their light, unless a pilot chose
  // otherwise (BdptSettings::light_choice).
  Distribution1D selection;
  Vec3 scene_center{0.f};
  float scene_radius = 1.f;

  bool empty() const { return all.empty(); }
  // The light (index into `all`) of emissive medium m; -1: none.
  int64_t volume_light_of(MediumHandle m) const {
    for (size_t i = 0; i < volume.size(); ++i)
      if (volume[i].medium == m) return int64_t(volume_to_all[i]);
    return -1;
  }
};

struct LightSample {
  Spectrum L{0.f};   // radiance (or intensity / dist^2) arriving at the reference point
  Vec3 wi{0.f};      // towards the light
  float pdf = 0.f;   // solid angle density at the reference point, times the selection pmf; 1 for delta lights
  Vec3 p_light{0.f};
  Vec3 n_light{0.f};
  float error_scale = 0.f;
  bool delta = false;
  bool infinite = false;  // no end point: the shadow ray is unbounded
  uint32_t light = 0;     // index into LightPools::all
  // A point of an emissive medium: L is 1, to be multiplied by sigma_a Le
  // there (the integrators look the medium up: emission per unit length),
  // and pdf is the density per unit volume times dist^2 (per unit solid
  // angle and unit length).
  bool volume = false;
};

// A point light's intensity leaving in world direction w, as colour (the
// functions that answer integrators turn colour into spectrum).
inline RGB point_intensity(const LightPools& L, const TexturePools& tex, const PointLight& pl, const Vec3& w) {
  return pl.profile < 0 ? pl.I : pl.I * profile_value(L.profiles[size_t(pl.profile)], tex, w);
}
// Its mean over all directions (power / 4 pi), averaged over the channels.
inline float point_mean_intensity(const LightPools& L, const PointLight& pl) {
  const float avg = (pl.I[0] + pl.I[1] + pl.I[2]) / 3.f;
  return pl.profile < 0 ? avg : avg * L.profiles[size_t(pl.profile)].mean_intensity;
}

// Emitted power (flux), averaged over the colour channels.
float light_power(const LightPools& lights, const LightRef& light, const TexturePools& tex);

// Builds the selection distribution (proportional to emitted power) and the
// environment-map sampling tables. Call once after all lights are added.
void finalize_lights(LightPools& lights, const ShapePools& shapes, const TexturePools& tex, Vec3 center, float radius);

// Chooses a light for the point p with shading normal n (zero: none) and
// samples a direction to it from p; L at the wavelengths l. u.x makes the
// choice and, rescaled, places the point; u_select stands in for it after
// an unlikely choice (light_choice.h).
std::optional<LightSample> sample_light(const LightPools& lights, const ShapePools& shapes, const TexturePools& tex,
                                        const LightSampler& sampler, const Vec3& p, const Vec3& n, LazyNumber u_select,
                                        Vec2 u, const SampledWavelengths& l, float u_volume = 0.5f);

// Density (solid angle at p, times the light sampler's pmf for (p, n)) that
// sample_light picks area light `area_index` at point p_light with normal
// n_light.
float area_light_pdf(const LightPools& lights, const ShapePools& shapes, const LightSampler& sampler,
                     uint32_t area_index, const Vec3& p, const Vec3& n, const Vec3& p_light, const Vec3& n_light);

// A point on area light a: uniform in area, or in a quadric's object-space
// area (which a non-uniform scale makes non-uniform in the world).
SurfacePoint sample_area_point(const ShapePools& shapes, const AreaLight& a, Vec2 u);
// The density per unit area with which sample_area_point places the point
// p of normal n.
float area_point_density(const ShapePools& shapes, const AreaLight& a, const Vec3& p, const Vec3& n);

// Radiance leaving an area light at a point of normal n and surface
// coordinates uv, in direction w, as colour.
inline RGB area_light_rgb(const AreaLight& l, const TexturePools& tex, const Vec3& n, Vec2 uv, const Vec3& w) {
  if (!l.two_sided && !(glm::dot(n, w) > 0.f)) return RGB(0.f);
  if (l.image < 0) return l.L;
  // As pbrt-v4: t flipped, bilinear, repeating.
  return l.L * tex.images[size_t(l.image)].lookup_rgb(Vec2(uv.x, 1.f - uv.y), ImageFilter::Bilinear, WrapMode::Repeat);
}

// The same at the wavelengths lambda.
inline Spectrum area_light_Le(const AreaLight& l, const TexturePools& tex, const Vec3& n, Vec2 uv, const Vec3& w,
                              const SampledWavelengths& lambda) {
  return light_spectrum(area_light_rgb(l, tex, n, uv, w), l.spectrum, tex, lambda);
}

// Radiance of infinite light `index` (into LightPools::infinite) along a
// ray from p leaving the scene in direction w (a portal light's only
// through its window), at wavelengths l. Each infinite light is a light of
// its own: a ray that escapes finds each of them, each weighted against
// the strategies that sample that light (a sum of several, weighted by
// their summed densities, would not match what next-event estimation and
// light subpaths, which choose one light, weigh: a constant sky beside an
// environment map came out 1.5% dark).
Spectrum infinite_light_Le(const LightPools& lights, const TexturePools& tex, uint32_t index, const Vec3& p,
                           const Vec3& w, const SampledWavelengths& l);
// The same for one given light (index into `all`), without the selection pmf.
std::optional<LightSample> sample_light_from(const LightPools& lights, const ShapePools& shapes, const TexturePools& tex,
                                             uint32_t light, const Vec3& p, Vec2 u, const SampledWavelengths& l,
                                             float u_volume = 0.5f);

// Density (times the light sampler's pmf) that sample_light produces
// direction w from p by choosing infinite light `index`.
float infinite_light_sampled_pdf(const LightPools& lights, const TexturePools& tex, const LightSampler& sampler,
                                 uint32_t index, const Vec3& p, const Vec3& w);
// Solid-angle density of direction w from p for infinite light `index`
// alone (no pmf).
float infinite_light_pdf(const LightPools& lights, const TexturePools& tex, uint32_t index, const Vec3& p, const Vec3& w);
// The density of direction w (towards the light) with which a light subpath
// leaves infinite light `index`: a portal light draws from its whole map.
float infinite_light_emission_dir_pdf(const LightPools& lights, const TexturePools& tex, uint32_t index, const Vec3& w);

// What the integrators ask of a light whatever its kind, answered here so
// that they never switch on LightKind:
//
// The medium light `light` (index into `all`) emits into along d from a
// point of normal n: a point or spot light's own, the side of an area
// light's shape that d leaves to; lights at infinity emit into vacuum
// (docs/media.md), and a volume light's is its medium's (its samples
// carry it).
MediumHandle emission_medium(const LightPools& lights, const ShapePools& shapes, uint32_t light, const Vec3& n,
                             const Vec3& d);
// Next-event estimation's density of light sample ls per unit area on an
// area light, per unit volume in a volume light, else (delta positions,
// lights at infinity) its own; dist2: the squared distance to the sample's
// point (1 at infinity).
float light_sample_density_at_light(const LightPools& lights, const LightSample& ls, float dist2);
// Whether light from `light` reaches p along -w_to_light: false only for a
// portal light whose window does not let it through.
bool reaches_through_portal(const LightPools& lights, uint32_t light, const Vec3& p, const Vec3& w_to_light);
// A volume light's sample carries L = 1 at its point: multiplies *L by
// sigma_a Le there, as the light's medium has it; *m is the light's medium
// and *sigma_t the extinction there. Whether the point really lies in that
// medium is decided by the ray that reaches it.
void complete_volume_sample(const LightPools& lights, const MediumPools& media, Spectrum* L, const Vec3& p,
                            uint32_t light, const SampledWavelengths& l, MediumHandle* m, Spectrum* sigma_t);
// The density per unit volume with which a volume light emits from p
// (without a selection pmf); zero when light `light` (or -1) is not one.
float volume_light_density(const LightPools& lights, int64_t light, const Vec3& p);

}  // namespace lantern
