// Primary sample space Metropolis (Kelemen, Szirmay-Kalos, Antal and
// Csonka 2002, "A Simple and Robust Mutation Strategy for the Metropolis
// Light Transport Algorithm"): a path is a deterministic function of the
// uniform numbers its sampler hands out, so a Markov chain over those
// numbers explores paths. This is one chain's vector of numbers, read
// through PathSampler (sampler.h) by dimension like any other sampler's.
//
// Each iteration proposes a mutation of the whole vector: a large step
// draws every number anew (an independent sample: the chain stays ergodic),
// a small step moves each by a normal deviate of standard deviation sigma,
// wrapped around [0, 1). Numbers are mutated lazily when they are read
// (Kelemen et al., section 4.2): one that was not read for n accepted small
// steps takes a single step of deviation sigma * sqrt(n), which has the
// distribution of the n steps it missed, and one last read before the
// latest accepted large step is drawn anew. Unlike the usual lazy scheme
// (pbrt's), the missed steps belong to the current state and survive a
// rejected proposal (get()); accept() keeps the proposal, reject()
// restores the state.
#pragma once

#include <cstdint>
#include <vector>

namespace lantern {

class MetropolisSampler {
 public:
  MetropolisSampler() = default;
  // `stream` names the random numbers: a chain started from bootstrap
  // sample i uses stream i for its first iteration, which then draws
  // exactly the numbers that sample drew.
  MetropolisSampler(uint64_t seed, uint64_t stream, float sigma, float large_step_probability);

  // Begins an iteration: a large step with the set probability, or a small
  // one. The first iteration of a sampler is always a large step.
  void start_iteration();
  // After the chain's first iteration: further random numbers come from
  // `stream`, so chains that started from the same bootstrap sample part.
  void reseed(uint64_t stream);

  // Number d of the current proposal.
  float get(uint32_t d);

  void accept();
  void reject();

  bool large_step() const { return large_step_; }
  // A uniform number of the chain's own, outside the primary sample
  // vector (the acceptance test, the choice of bootstrap sample).
  float uniform();

 private:
  struct Number {
    float value = 0.f, backup = 0.f;
    int32_t modified = -1, backup_modified = -1;  // (accepted) iteration of the last change
  };
  float normal();

  std::vector<Number> x_;
  uint64_t seed_ = 0, key_ = 0, counter_ = 0;
  float sigma_ = 0.01f, large_step_probability_ = 0.3f;
  // Iterations count accepted proposals (reject() takes one back): 2^31 of
  // them is far beyond any chain's length.
  int32_t iteration_ = -1, last_large_step_ = 0;
  bool large_step_ = true;
  float spare_normal_ = 0.f;  // Box and Muller make two at a time
  bool has_spare_ = false;
};

}  // namespace lantern
