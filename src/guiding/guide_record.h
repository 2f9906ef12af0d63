// What a path tells the guiding field about one of its vertices: the
// radiance that arrived along the direction it continued in, over the
// density it chose that direction with (a one-sample estimate of the
// radiance integrated over the direction's cell), and where it goes in the
// field being built. Waves make records in parallel; the renderer adds them
// in wave order, so the sums, and the field, do not depend on threads.
#pragma once

#include <cstdint>

namespace lantern {

struct GuideRecord {
  uint32_t leaf;  // the spatial leaf (SDTree::leaf_of)
  // The cell of its directional tree for the vertex's normal
  // (DirectionalTree::cell_of), or for a mixture its direction, packed
  // (VmfMixture::cell_of).
  uint32_t cell;
  float energy;
  // For the choice of the BSDF's share α: the squared estimate times the
  // mixture density it was drawn with, (f |cos| L)^2 / p_mix (Inf where too
  // large for a float: left out), and the two densities of its direction
  // (guide_pdf -1: drawn without a guide).
  float second, bsdf_pdf, guide_pdf;
  uint8_t bin;  // that normal's bin (SDTree::normal_bin)
  // For a mixture of lobes: the inverse distance, from the leaf's pivot,
  // of where the path went on from (0: nowhere known; guiding/vmf_mixture.h).
  float inv_distance = 0.f;
  // For whether guiding pays at all (SDTree::judge): the square of what
  // the path brought the image after this vertex, (beta L)^2 (beta the
  // throughput after it; Inf where too large for a float: left out), and
  // the density its direction was drawn with.
  float image = 0.f, drawn_pdf = 0.f;
};

// The bin of a record of guided distances: the radiance a medium vertex
// scattered (energy), for the leaf of the scattered radiance field
// (guiding/scatter_field.h); no direction.
inline constexpr uint8_t kScatteredRecord = 255;

}  // namespace lantern
