// The integrators' rule for emissive media (docs/media.md, "Emissive
// media"): light samples on a volume light carry L = 1 and are completed
// by the light with sigma_a Le at their point; whether the point really
// lies in that medium is decided by the ray that reaches it
// (trace_transmittance's end medium, or locate_media).
//
// Paths that end on volume emission follow pbrt-v4's volpath: emission at a
// point of a medium counts only while the path could still scatter there,
// so such paths have at most maxdepth segments (one fewer than paths that
// end on a surface emitter).
#pragma once

namespace lantern {

// Whether a path may end on a volume light's point sampled by next-event
// estimation from the eye vertex at depth `vertex` (1: the camera ray's
// hit, as both integrators count): that path has vertex + 1
// segments, at most maxdepth. (Completing such a sample is the light's:
// complete_volume_sample, light/lights.h.)
inline bool volume_sample_allowed(int vertex, int maxdepth) { return vertex + 1 <= maxdepth; }

}  // namespace lantern
