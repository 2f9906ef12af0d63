#include "integrator/light_choice_pilot.h"

#include <algorithm>
#include <cmath>

#include "integrator/pilot.h"
#include "math/rng.h"

namespace lantern {

std::vector<float> power_choice(const LightPools& lights) {
  std::vector<float> p(lights.all.size());
  for (size_t j = 0; j < p.size(); ++j) p[j] = lights.selection.discrete_pmf(j);
  return p;
}

namespace {
// Uniform over the lights with power: a light without has nothing to emit.
std::vector<float> uniform_over(std::vector<float> power) {
  const float lit = float(std::count_if(power.begin(), power.end(), [](float x) { return x > 0.f; }));
  for (float& x : power) x = x > 0.f ? 1.f / lit : 0.f;
  return power;
}
}  // namespace

std::vector<float> uniform_choice(const LightPools& lights) { return uniform_over(power_choice(lights)); }

std::vector<float> first_pass_choice(const LightPools& lights) {
  std::vector<float> p = power_choice(lights);
  const std::vector<float> u = uniform_choice(lights);
  for (size_t j = 0; j < p.size(); ++j) p[j] = 0.5f * p[j] + 0.5f * u[j];
  return p;
}

std::vector<double> light_choice_target(const Scene& scene, const LightSampler& light_sampler,
                                        const BdptSettings& pilot, uint32_t spp, RayBackend backend) {
  BdptSettings s = pilot;
  s.planned_spp = spp;
  s.seed = hash_key(pilot.seed, 0x6C696768ULL, 0);  // (numbers of its own)
  s.record_strategies = true;
  s.light_subpath_rate = 1.f;
  const Bdpt bdpt(scene, light_sampler, s);
  std::vector<double> square(scene.lights.all.size(), 0.0);
  auto add = [&](uint32_t light, double v) {
    if (light < square.size() && std::isfinite(v * v)) square[light] += v * v;
  };
  trace_pilot(scene, bdpt, tile_order(s.width, s.height), spp, backend,
              [&](const WaveDesc& wave, size_t, const WaveOutput& out) {
                // Per camera sample: what its light subpath's strategies
                // brought it (B), and that subpath's light; splats alone.
                std::vector<double> b(wave.size(), 0.0);
                std::vector<uint32_t> light(wave.size(), kNoLight);
                for (const StrategyRecord& r : out.strategies) {
                  if (r.s < 2) continue;
                  const double v = double(average(r.weighted));
                  if (r.t == 1)
                    add(r.light, v);
                  else if (r.slot < wave.size() && std::isfinite(v)) {
                    b[r.slot] += v;
                    light[r.slot] = r.light;
                  }
                }
                for (uint32_t slot = 0; slot < wave.size(); ++slot) add(light[slot], b[slot]);
              });
  std::vector<double> target(square.size(), 0.0);
  double total = 0.0;
  for (size_t j = 0; j < target.size(); ++j) total += target[j] = std::sqrt(double(s.light_choice[j]) * square[j]);
  if (total > 0.0 && std::isfinite(total))
    for (double& t : target) t /= total;
  else
    std::fill(target.begin(), target.end(), 0.0);
  return target;
}

LightChoices light_choice_candidates(const std::vector<float>& power, const std::vector<double>& target) {
  LightChoices c;
  const size_t n = power.size();
  c.names.push_back("power");
  c.probabilities.push_back(power);
  std::vector<float> mixed(n), measured(n);
  const bool any_target = std::any_of(target.begin(), target.end(), [](double t) { return t > 0.0; });
  for (size_t j = 0; j < n; ++j) {
    // (a light without power emits nothing: no target gives it a share)
    const float t = power[j] > 0.f && any_target ? float(target[j]) : power[j];
    mixed[j] = 0.5f * power[j] + 0.5f * t;
    measured[j] = 0.1f * power[j] + 0.9f * t;
  }
  c.names.push_back("uniform");
  c.probabilities.push_back(uniform_over(power));
  c.names.push_back("mixed");  // half power, half measured
  c.probabilities.push_back(mixed);
  c.names.push_back("measured");
  c.probabilities.push_back(measured);
  return c;
}

std::vector<std::vector<float>> light_choice_ratios(const LightChoices& choices, const std::vector<float>& pilot) {
  std::vector<std::vector<float>> ratios;
  for (const std::vector<float>& p : choices.probabilities) {
    std::vector<float> rho(p.size(), 1.f);
    for (size_t j = 0; j < p.size() && j < pilot.size(); ++j) rho[j] = pilot[j] > 0.f ? p[j] / pilot[j] : 1.f;
    ratios.push_back(std::move(rho));
  }
  return ratios;
}

}  // namespace lantern
