// One of a path's numbers, drawn when it is read. Many are never read: a
// light's point takes its first coordinate from what the choice of light
// left (light/light_choice.h), a BSDF of one lobe has no component to
// choose, roulette does not play at the first bounces nor on bright paths.
// Every sampler but metropolis draws a number as a pure function of its
// dimension, so one left unread changes no other and images stay the same
// bit for bit; a metropolis chain draws its numbers in the order they are
// read, and reads fewer. A plain float is a number already drawn.
#pragma once

#include <cstdint>

namespace lantern {

class LazyNumber {
 public:
  LazyNumber(float value) : value_(value) {}  // NOLINT(google-explicit-constructor): a number already drawn
  // Dimension `dimension` of `source`, which has float get1d(uint32_t) const
  // and outlives this number.
  template <class Source>
  LazyNumber(const Source& source, uint32_t dimension)
      : source_(&source), dimension_(dimension), draw_(&draw_from<Source>) {}

  float operator()() const { return draw_ ? draw_(source_, dimension_) : value_; }

 private:
  template <class Source>
  static float draw_from(const void* source, uint32_t dimension) {
    return static_cast<const Source*>(source)->get1d(dimension);
  }

  const void* source_ = nullptr;
  uint32_t dimension_ = 0;
  float value_ = 0.f;
  float (*draw_)(const void*, uint32_t) = nullptr;
};

}  // namespace lantern
