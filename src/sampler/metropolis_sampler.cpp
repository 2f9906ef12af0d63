#include "sampler/metropolis_sampler.h"

#include <cmath>

#include "math/common.h"
#include "math/rng.h"

namespace lantern {

MetropolisSampler::MetropolisSampler(uint64_t seed, uint64_t stream, float sigma, float large_step_probability)
    : seed_(seed), key_(hash_key(seed, stream, 0x4D4C54ULL)), sigma_(sigma), large_step_probability_(large_step_probability) {
  x_.reserve(64);  // (a bidirectional sample of a few bounces reads about as many)
}

float MetropolisSampler::uniform() { return bits_to_unit_float(mix64(key_ ^ (++counter_ * 0x9E3779B97F4A7C15ULL))); }

// Box and Muller's transform: two independent normal deviates from two
// uniform numbers, the second kept for the next call.
float MetropolisSampler::normal() {
  if (has_spare_) {
    has_spare_ = false;
    return spare_normal_;
  }
  const float r = std::sqrt(-2.f * std::log(1.f - uniform()));  // (1 - u in (0, 1])
  const float phi = 2.f * kPi * uniform();
  spare_normal_ = r * std::sin(phi);
  has_spare_ = true;
  return r * std::cos(phi);
}

void MetropolisSampler::reseed(uint64_t stream) {
  key_ = hash_key(seed_, stream, 0x52455345ULL);
  counter_ = 0;
  has_spare_ = false;
}

void MetropolisSampler::start_iteration() {
  ++iteration_;
  large_step_ = iteration_ == 0 || uniform() < large_step_probability_;
}

// Wraps a moved number back into [0, 1).
static float wrap(float x) {
  x -= std::floor(x);
  return x < 1.f ? x : 0.f;  // (rounding of a value just below 0)
}

float MetropolisSampler::get(uint32_t d) {
  if (d >= x_.size()) x_.resize(size_t(d) + 1);
  Number& x = x_[d];
  if (x.modified < iteration_) {
    // First the number's value in the current state, as mutating every
    // number at every accepted iteration would have made it: drawn anew at
    // the latest accepted large step if it was last set before it, then
    // moved by the accepted small steps since. This part is the state's
    // and stays when the proposal is rejected: were it drawn again at each
    // proposal, a number that some paths never read would wander more than
    // its steps allow, and the chain would not keep its target density.
    if (x.modified < last_large_step_) {
      x.value = uniform();
      x.modified = last_large_step_;
    }
    const int32_t missed = iteration_ - 1 - x.modified;
    if (missed > 0) {
      x.value = wrap(x.value + normal() * sigma_ * std::sqrt(float(missed)));
      x.modified = iteration_ - 1;
    }
    // Then this proposal's own step, undone by reject().
    x.backup = x.value;
    x.backup_modified = x.modified;
    x.value = large_step_ ? uniform() : wrap(x.value + normal() * sigma_);
    x.modified = iteration_;
  }
  return x.value;
}

void MetropolisSampler::accept() {
  if (large_step_) last_large_step_ = iteration_;
}

void MetropolisSampler::reject() {
  for (Number& x : x_)
    if (x.modified == iteration_) {
      x.value = x.backup;
      x.modified = x.backup_modified;
    }
  --iteration_;
}

}  // namespace lantern
