// What the integrators add for emissive media (docs/media.md, "Emissive
// media"): light samples on a volume light carry L = 1 and are
// completed here with sigma_a Le at their point, as the light's medium has
// it there; whether the point really lies in that medium is decided by the
// ray that reaches it (trace_transmittance's end medium, or locate_media).
//
// Paths that end on volume emission follow pbrt-v4's volpath: emission at a
// point of a medium counts only while the path could still scatter there,
// so such paths have at most maxdepth segments (one fewer than paths that
// end on a surface emitter).
#pragma once

#include "scene/scene.h"

namespace lantern {

// Multiplies a volume light sample's L by sigma_a Le at its point; *m is
// the light's medium and *sigma_t the extinction there.
inline void complete_volume_sample(const Scene& sc, RGB* L, const Vec3& p, uint32_t light, MediumHandle* m, RGB* sigma_t) {
  const VolumeLight& v = sc.lights.volume[sc.lights.all[light].index];
  RGB a, s;
  sc.media.coefficients_at(v.medium, p, &a, &s);
  *L *= a * sc.media.Le(v.medium, p);
  *m = v.medium;
  *sigma_t = a + s;
}

// The density per unit volume with which a volume light emits from p
// (without a selection pmf); zero when light `light` (index into
// LightPools::all, or -1) is not one.
inline float volume_light_density(const Scene& sc, int64_t light, const Vec3& p) {
  if (light < 0) return 0.f;
  return volume_point_density(sc.lights.volume[sc.lights.all[size_t(light)].index], p);
}

}  // namespace lantern
