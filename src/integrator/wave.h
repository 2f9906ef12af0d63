// A wave: the unit of parallel work. It covers a run of pixels (in tile
// order) times a run of sample indices; slot = pixel_in_wave * samples +
// sample_in_wave, so a pixel's samples are adjacent and in index order.
#pragma once

#include <algorithm>
#include <cstdint>
#include <memory>
#include <utility>
#include <vector>

namespace lantern {

class MetropolisSampler;

struct WaveDesc {
  const uint32_t* pixels;  // pixel indices (y * width + x)
  uint32_t pixel_count;
  uint32_t first_sample;
  uint32_t samples;  // per pixel
  // Metropolis (integrator/metropolis.h): slot k's numbers are chain k's
  // proposal, its camera sample anywhere on the image; null otherwise.
  MetropolisSampler* chains = nullptr;
  // Adaptive sampling's halves (Film::track_halves): a sample is in the odd
  // half when its index has this bit (halves_bit).
  uint32_t half_bit = 1;
  bool odd(uint32_t sample_index) const { return (sample_index & half_bit) != 0; }
  // Adaptive merging (vcm, bpm, ppm): a byte a pixel (y * width + x), the
  // pixels whose camera samples this wave takes; every slot still traces
  // its light subpath. Null: all.
  const uint8_t* eye_pixels = nullptr;
  bool takes_eye(uint32_t pixel) const { return !eye_pixels || eye_pixels[pixel]; }
  uint32_t size() const { return pixel_count * samples; }
};

// The bit of a sample's index that puts it in one half of its pixel's
// samples or the other: half a pass's samples when a pass is a power of
// two of them, so that each half of a pass is a run of consecutive
// indices (with the low-discrepancy samplers, a pattern as good as a
// whole pass of half the samples, where the odd and even indices of one
// are worse: the estimate of the Cornell box in bdpt at 64 spp with zsobol
// went from 1.85 to 1.25 times its error); never below `split`, the paths
// a camera sample splits into, which must stay in one half.
inline uint32_t halves_bit(uint32_t pass_spp, uint32_t split) {
  const bool power_of_two = pass_spp > 1 && (pass_spp & (pass_spp - 1)) == 0;
  return std::max(power_of_two ? pass_spp / 2 : 1u, split);
}

// Pixel indices in 16x16 tiles, row-major inside a tile: neighbouring
// camera rays stay together in a wave, which keeps primary rays coherent.
std::vector<uint32_t> tile_order(int width, int height, int tile = 16);

// A thread's pools for its waves (PathWave, BdptWave), behind a pointer
// whose type an integrator's header can name before the pools' own header
// is included; media's pools only for a scene that has media.
template <class Pools>
using WavePools = std::unique_ptr<Pools, void (*)(Pools*)>;
template <class Pools, class Stream>
WavePools<Pools> make_wave_pools(uint32_t capacity, Stream stream, bool media) {
  WavePools<Pools> w{new Pools(capacity, std::move(stream)), [](Pools* p) { delete p; }};
  if (media) w->resize_media(capacity);
  return w;
}

}  // namespace lantern
