#include "integrator/metropolis.h"

#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "integrator/bdpt_wave.h"
#include "integrator/pass_context.h"
#include "math/distribution.h"
#include "math/rng.h"

namespace lantern {

namespace {

// One splat of a sample: where it lands and what it carries.
struct Contribution {
  Vec2 p;
  RGB v;
};

// The luminance of the magnitudes: positive wherever a sample carries
// anything, so that no contribution lies where the chains cannot go.
float importance(const RGB& v) { return 0.2126f * std::fabs(v[0]) + 0.7152f * std::fabs(v[1]) + 0.0722f * std::fabs(v[2]); }

// A wave's splats sorted by slot (its proposals), each proposal's
// importance beside them.
struct Proposals {
  std::vector<uint32_t> begin;  // slot k's are [begin[k], begin[k + 1])
  std::vector<Contribution> all;
  std::vector<float> I;
  std::vector<uint32_t> next;  // (scratch)

  void gather(const WaveOutput& out, uint32_t slots) {
    begin.assign(size_t(slots) + 1, 0u);
    for (uint32_t s : out.splat_slots) ++begin[s + 1];
    for (uint32_t k = 0; k < slots; ++k) begin[k + 1] += begin[k];
    all.resize(out.splats.size());
    next.assign(begin.begin(), begin.end() - 1);
    for (size_t j = 0; j < out.splats.size(); ++j) all[next[out.splat_slots[j]]++] = {out.splats[j].p_raster, out.splats[j].L};
    I.assign(slots, 0.f);
    for (uint32_t k = 0; k < slots; ++k) {
      float sum = 0.f;
      for (uint32_t j = begin[k]; j < begin[k + 1]; ++j) sum += importance(all[j].v);
      // A sample that is not finite is not proposed (the film would drop it).
      I[k] = std::isfinite(sum) ? sum : 0.f;
    }
  }
};

// A thread's wave state and buffers.
struct Worker {
  WavePools<BdptWave> wave;
  WaveOutput out;
  Proposals proposals;
  std::vector<uint32_t> pixels;  // (unused by a Metropolis wave; zeros)
};

// Chains traced together as one wave; their state between iterations.
struct ChainGroup {
  uint32_t first = 0;                     // its first chain's number
  std::vector<MetropolisSampler> chains;  // contiguous: WaveDesc::chains
  std::vector<std::vector<Contribution>> current;
  std::vector<float> I;                   // of the current samples
  std::vector<uint64_t> left;             // proposals each chain has yet to make
  uint64_t proposals = 0, accepted = 0, traced = 0;
};

class Chains {
 public:
  Chains(const Bdpt& bdpt, const MetropolisSettings& s, PassContext& cx)
      : bdpt_(bdpt), s_(s), cx_(cx),
        workers_([&] {
          Worker w{make_thread_state(bdpt, kWaveCapacity, cx), {}, {}, std::vector<uint32_t>(kWaveCapacity, 0u)};
          w.out.keep_slots = true;
          return w;
        }) {}

  bool run();

 private:
  static constexpr uint32_t kWaveCapacity = 1024;  // bootstrap waves; groups are at most this large

  bool stop() const {
    return cx_.stop_requested() || (cx_.opt.time_limit_seconds > 0 && cx_.checkpoints.elapsed() >= cx_.opt.time_limit_seconds);
  }
  // Traces the proposals of `chains` (n of them) on this thread.
  Worker& trace(MetropolisSampler* chains, uint32_t n, uint32_t iteration) {
    Worker& w = workers_.local();
    w.out.clear();
    WaveDesc wave{w.pixels.data(), n, iteration, 1};
    wave.chains = chains;
    bdpt_.trace(wave, *w.wave, w.out);
    w.proposals.gather(w.out, n);
    return w;
  }
  void bootstrap();
  void start(ChainGroup& g, const Distribution1D& choose);
  void step(ChainGroup& g);

  const Bdpt& bdpt_;
  const MetropolisSettings& s_;
  PassContext& cx_;
  tbb::enumerable_thread_specific<Worker> workers_;
  std::vector<float> bootstrap_I_;
  double b_ = 0.0;  // the mean importance
  std::vector<ChainGroup> groups_;
};

// Independent samples (each a chain's first, large step), their importance
// kept: its mean is b, and the chains start from them.
void Chains::bootstrap() {
  const uint64_t n = s_.bootstrap_samples;
  bootstrap_I_.assign(n, 0.f);
  const uint64_t waves = (n + kWaveCapacity - 1) / kWaveCapacity;
  tbb::parallel_for(tbb::blocked_range<uint64_t>(0, waves, 1), [&](const tbb::blocked_range<uint64_t>& r) {
    std::vector<MetropolisSampler> samplers;
    for (uint64_t wi = r.begin(); wi != r.end() && !cx_.stop_requested(); ++wi) {
      const uint64_t first = wi * kWaveCapacity;
      const uint32_t count = uint32_t(std::min<uint64_t>(kWaveCapacity, n - first));
      samplers.clear();
      for (uint32_t k = 0; k < count; ++k) {
        samplers.emplace_back(s_.seed, first + k, s_.sigma, s_.large_step_probability);
        samplers.back().start_iteration();
      }
      Worker& w = trace(samplers.data(), count, 0);
      std::copy(w.proposals.I.begin(), w.proposals.I.end(), bootstrap_I_.begin() + std::ptrdiff_t(first));
    }
  });
  double sum = 0.0;  // (in index order: the same bits for any thread count)
  for (float i : bootstrap_I_) sum += double(i);
  b_ = n > 0 ? sum / double(n) : 0.0;
}

// Each chain's first state: a bootstrap sample chosen in proportion to its
// importance, traced again from its own numbers.
void Chains::start(ChainGroup& g, const Distribution1D& choose) {
  const uint32_t n = uint32_t(g.chains.size());
  for (uint32_t k = 0; k < n; ++k) {
    const uint64_t chain = g.first + k;
    float pmf = 0.f;
    const size_t index = choose.sample_discrete(bits_to_unit_float(hash_key(s_.seed, chain, 0x424F4F54ULL)), &pmf);
    g.chains[k] = MetropolisSampler(s_.seed, index, s_.sigma, s_.large_step_probability);
    g.chains[k].start_iteration();
  }
  Worker& w = trace(g.chains.data(), n, 0);
  const Proposals& p = w.proposals;
  for (uint32_t k = 0; k < n; ++k) {
    g.current[k].assign(p.all.begin() + p.begin[k], p.all.begin() + p.begin[k + 1]);
    g.I[k] = p.I[k];
    g.chains[k].accept();
    g.chains[k].reseed(g.first + k);
  }
}

// One proposal of every chain of the group that has one left.
void Chains::step(ChainGroup& g) {
  const uint32_t n = uint32_t(g.chains.size());
  for (uint32_t k = 0; k < n; ++k) g.chains[k].start_iteration();
  Worker& w = trace(g.chains.data(), n, uint32_t(g.proposals / n));
  const Proposals& p = w.proposals;
  WaveOutput& film_out = w.out;
  film_out.clear();
  uint32_t made = 0;
  for (uint32_t k = 0; k < n; ++k) {
    MetropolisSampler& chain = g.chains[k];
    if (g.left[k] == 0) {  // (its share is done: this proposal is not counted)
      chain.reject();
      continue;
    }
    --g.left[k];
    ++made;
    const float I_new = p.I[k], I_old = g.I[k];
    const float a = I_old > 0.f ? std::min(1.f, I_new / I_old) : 1.f;
    // Kelemen et al.'s weights (section 5): large steps are independent
    // samples of density 1, the chain's states have density I / b, and
    // each sample is weighted by the balance heuristic over the two, so
    // that dim parts of the image, which the chains seldom visit, get the
    // large steps' samples at their full weight.
    const double p_large = s_.large_step_probability;
    const double w_new = (double(a) + (chain.large_step() ? 1.0 : 0.0)) / (double(I_new) / b_ + p_large);
    const double w_old = double(1.f - a) / (double(I_old) / b_ + p_large);
    if (I_new > 0.f && w_new > 0.0)
      for (uint32_t j = p.begin[k]; j < p.begin[k + 1]; ++j)
        film_out.splats.push_back({p.all[j].p, p.all[j].v * float(w_new), false});
    if (w_old > 0.0)
      for (const Contribution& c : g.current[k]) film_out.splats.push_back({c.p, c.v * float(w_old), false});
    if (chain.uniform() < a) {
      g.current[k].assign(p.all.begin() + p.begin[k], p.all.begin() + p.begin[k + 1]);
      g.I[k] = I_new;
      chain.accept();
      ++g.accepted;
    } else {
      chain.reject();
    }
  }
  g.proposals += made;
  g.traced += n;
  film_out.light_paths = made;
  cx_.film.prepare(film_out);
  {
    std::lock_guard<std::mutex> lock(cx_.film_mutex);
    cx_.film.merge(film_out);
  }
  cx_.done += made;
}

bool Chains::run() {
  bootstrap();
  if (cx_.stop_requested()) return true;  // (a bootstrap cut short has no mean to start from)
  const uint64_t total = s_.mutations;
  const uint32_t chains = total > 0 ? uint32_t(std::min<uint64_t>(s_.chains, total)) : s_.chains;
  if (!(b_ > 0.0) || chains == 0) {  // nothing carries light: a black image of all its proposals
    WaveOutput out;
    out.light_paths = total;
    std::lock_guard<std::mutex> lock(cx_.film_mutex);
    cx_.film.merge(out);
    return false;
  }
  // Groups: a few per thread, so that threads share the work evenly;
  // how the chains are grouped does not change the image.
  const uint32_t threads = uint32_t(std::max(1, tbb::this_task_arena::max_concurrency()));
  const uint32_t size = std::clamp<uint32_t>((chains + 4 * threads - 1) / (4 * threads), 1u, kWaveCapacity);
  for (uint32_t first = 0; first < chains; first += size) {
    ChainGroup& g = groups_.emplace_back();
    const uint32_t n = std::min(size, chains - first);
    g.first = first;
    g.chains.resize(n);
    g.current.resize(n);
    g.I.assign(n, 0.f);
    for (uint32_t k = 0; k < n; ++k) {  // pbrt-v4's shares of the proposals
      const uint64_t c = first + k;
      g.left.push_back(total > 0 ? (c + 1) * total / chains - c * total / chains : UINT64_MAX);
    }
  }
  const Distribution1D choose(bootstrap_I_);
  tbb::parallel_for(size_t(0), groups_.size(), [&](size_t i) { start(groups_[i], choose); });
  // Rounds of a few proposals per chain, so that a time budget or a stop
  // ends every chain at about the same length.
  constexpr uint32_t kRound = 8;
  // A time budget shorter than the set-up still gets one proposal of
  // every chain, so that every run adds to the image.
  bool stopped = false;
  for (bool more = true, first = true; more && !stopped; first = false) {
    tbb::parallel_for(size_t(0), groups_.size(), [&](size_t i) {
      ChainGroup& g = groups_[i];
      for (uint32_t r = 0; r < kRound && *std::max_element(g.left.begin(), g.left.end()) > 0; ++r) {
        if (!(first && r == 0) && stop()) break;
        step(g);
      }
    });
    more = false;
    for (const ChainGroup& g : groups_) more = more || *std::max_element(g.left.begin(), g.left.end()) > 0;
    stopped = more && stop();
  }
  uint64_t proposals = 0, accepted = 0;
  uint64_t traced = 0;
  for (const ChainGroup& g : groups_) proposals += g.proposals, accepted += g.accepted, traced += g.traced;
  cx_.stats.mlt_b = b_;
  cx_.stats.mlt_proposals = proposals;
  cx_.stats.mlt_accepted = accepted;
  cx_.stats.mlt_chains = chains;
  cx_.stats.mlt_traced = s_.bootstrap_samples + chains + traced;
  std::vector<BdptWave*> states;
  for (Worker& w : workers_) states.push_back(w.wave.get());
  gather_stats(states, 0.0, cx_.stats);
  return stopped;
}

}  // namespace

bool run_metropolis(const Bdpt& bdpt, const MetropolisSettings& settings, PassContext& cx) {
  Chains chains(bdpt, settings, cx);
  return chains.run();
}

}  // namespace lantern
