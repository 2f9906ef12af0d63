// How a render lays its samples out (run_passes.h): in passes,
// each a range of sample indices of every pixel, and each pass in waves,
// runs of pixels of the tile order. Units, the waves numbered through the
// whole render, are what checkpoints, MPI's tickets and --part count.
//
// A pass is one sample per pixel for merging (vcm, bpm, ppm): a pixel's
// samples then merge with the light vertices of as many different waves,
// whatever the budget, and the merging radius shrinks sample by sample.
// Under a time budget it is one camera sample per pixel: its `split`
// paths (docs/splitting.md). Otherwise up to 16, a pixel's samples
// adjacent in its wave (coherent rays, fewer passes); so too adaptive
// sampling under a time budget, whose pixels differ in samples anyway: a
// pass of one sample would be a wave or two, too few to keep the threads
// busy (a timed adaptive render drew 30% fewer samples so).
//
// A guided render's field learns in iterations of doubling length from
// one sample per pixel (integrator/guiding_field.h), so its passes are of
// one sample while it learns. Once it has learnt (its last iteration
// ended, or its guide stopped where it does not pay: SDTree::judge), the
// render goes on in the passes an unguided render of its budget takes,
// from the first sample their size divides: a second layout, whose units
// follow the first's. The path tracer's camera samples then split as an
// unguided render's do, whether its guide stopped or goes on (a guided
// path's first hit is shared as an unguided one's, and each path samples
// the guide there with its own numbers). Both the moment and the
// new passes follow from the field's state (its iteration, whether it
// learns, whether its guide stopped), which checkpoints keep and MPI's
// ranks share, so a resumed run and every rank lay the render out alike.
// Under adaptive sampling, which decides a pass's pixels two passes ahead
// (adaptive_sampling.h), the second layout begins after the samples
// already decided when the field is known to have learnt: those were
// decided as passes of one sample (relayout_from).
#pragma once

#include <algorithm>
#include <cstdint>

#include "integrator/render_settings.h"

namespace lantern {

// The samples per pixel of a pass (above). learning: a guided render's
// field still learns; adaptive: adaptive sampling is on.
inline uint32_t pass_samples(bool merging, bool learning, bool timed, bool adaptive, uint32_t split,
                             uint32_t total_spp) {
  if (merging || learning) return 1;
  if (timed && !adaptive) return split;
  return std::min<uint32_t>(total_spp, 16u);
}

// Where the second layout begins after a field that learnt `learnt`
// passes (of one sample): the first multiple of its `pass_spp` from there
// on; under adaptive sampling from learnt + 3 on. (The field is known to
// have learnt once its last pass, learnt - 1, is merged; by then adaptive
// sampling has decided the pixels of the pair of samples after that pass's
// pair, up to sample learnt + 2 when learnt is odd, as it is after an
// iteration: 2^k - 1; and at an even sample, where a pair begins.)
inline uint64_t relayout_from(uint64_t learnt, uint32_t pass_spp, bool adaptive) {
  const uint64_t after = learnt + (adaptive ? 3 : 0);
  const uint64_t step = adaptive && pass_spp % 2 ? 2 * uint64_t(pass_spp) : pass_spp;
  return (after + step - 1) / step * step;
}

struct PassLayout {
  uint32_t pass_spp = 1;
  uint32_t pixels_per_wave = 1;
  uint32_t waves = 1;         // of a pass
  uint32_t first_sample = 0;  // where the layout's first pass begins
  uint64_t first_pass = 0;    // that pass's number in the render
  uint64_t first_unit = 0;    // the unit of its first wave

  // The pass that begins at sample `first`, and the unit of its wave `wave`.
  uint64_t pass_of(uint32_t first) const { return first_pass + (first - first_sample) / pass_spp; }
  uint64_t unit_of(uint32_t first, uint32_t wave) const {
    return first_unit + uint64_t((first - first_sample) / pass_spp) * waves + wave;
  }
  // The paths of its largest wave.
  uint32_t capacity() const { return pixels_per_wave * pass_spp; }
  // The render's units up to `total_spp` samples per pixel, with this
  // layout to the end.
  uint64_t units_to(uint32_t total_spp) const {
    const uint64_t passes = total_spp > first_sample ? (total_spp - first_sample + pass_spp - 1) / pass_spp : 0;
    return first_unit + passes * waves;
  }
};

// The layout of passes of `pass_spp` samples over `pixels` pixels from
// sample `from` on, after `before`'s passes up to there (none for the
// first layout; `from` a multiple of pass_spp and of before's).
inline PassLayout pass_layout(uint32_t pass_spp, uint32_t pixels, bool merging, int wave_size,
                              const PassLayout* before = nullptr, uint32_t from = 0) {
  PassLayout l;
  l.pass_spp = pass_spp;
  l.pixels_per_wave = merging ? merging_wave_paths(pixels, wave_size)
                              : std::max<uint32_t>(1, uint32_t(std::max(wave_size, 1)) / pass_spp);
  l.waves = (pixels + l.pixels_per_wave - 1) / l.pixels_per_wave;
  if (before) {
    l.first_sample = from;
    l.first_pass = before->pass_of(from);
    l.first_unit = before->unit_of(from, 0);
  }
  return l;
}

// The most units a guided render of `total_spp` samples per pixel (not
// under a time budget) may number: `learning`, its layout of passes of one
// sample, to the end, or `after` from wherever the field stops learning
// (the end of an iteration, 2^k - 1) on. A checkpoint's bound on its units
// (Checkpointer::set_units), the same before and after the relayout.
inline uint64_t most_guided_units(const PassLayout& learning, uint32_t pass_spp, uint32_t pixels, bool merging,
                                  int wave_size, uint32_t total_spp, bool adaptive = false) {
  uint64_t most = learning.units_to(total_spp);
  for (uint64_t learnt = 0; learnt < total_spp; learnt = 2 * learnt + 1) {
    const uint64_t from = relayout_from(learnt, pass_spp, adaptive);
    if (from >= total_spp) break;
    const PassLayout after = pass_layout(pass_spp, pixels, merging, wave_size, &learning, uint32_t(from));
    most = std::max(most, after.units_to(total_spp));
  }
  return most;
}

}  // namespace lantern
