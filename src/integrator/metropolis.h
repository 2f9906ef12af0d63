// Metropolis light transport in primary sample space over bidirectional
// path tracing (Kelemen et al. 2002; pbrt-v4's `mlt` integrator and its
// parameters). docs/mlt.md.
//
// A bidirectional sample is a function of the uniform numbers it reads:
// its camera sample (anywhere on the image), its light subpath, its eye
// subpath and every strategy's contribution, each a splat on the image.
// Chains of such numbers (sampler/metropolis_sampler.h) are mutated and
// accepted in proportion to the scalar importance I of all a sample's
// splats together (the sum of their luminances); every proposal adds both
// the proposed and the current sample, weighted by the acceptance
// probability and its complement (Veach 1997, section 11.3.3, the expected
// values), each scaled by b / I, where b is the mean of I over independent
// bootstrap samples, from which the chains also draw their first states in
// proportion to I (so they start in the stationary distribution). The film
// divides by the proposals: a pixel is then the image's pixels times the
// mean of b / I times what lands on it, whose expectation under the chain's
// stationary density I / b is the pixel's value.
//
// Where pbrt-v4 evaluates one strategy of one path length per proposal,
// here each proposal is a whole bidirectional sample with every strategy
// weighted by MIS: the wavefront traces a group of chains' proposals
// together as one wave. A chain's numbers depend on its own reads only, and
// the film's sums on no order, so the image is the same for any thread
// count and any grouping.
#pragma once

#include <cstdint>

#include "integrator/bdpt.h"

namespace lantern {

struct MetropolisSettings {
  uint64_t mutations = 0;  // proposals in all (mutations per pixel times the film's pixels); 0: until the time is up
  uint32_t chains = 1000;
  uint64_t bootstrap_samples = 100000;
  float large_step_probability = 0.3f;
  float sigma = 0.01f;  // of a small step, per number
  uint64_t seed = 0;
};

struct PassContext;  // integrator/pass_context.h

// Runs the chains into cx.film; true if it stopped early (time, cancel).
bool run_metropolis(const Bdpt& bdpt, const MetropolisSettings& settings, PassContext& cx);

}  // namespace lantern
