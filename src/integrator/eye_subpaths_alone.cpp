#include "integrator/eye_subpaths_alone.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "integrator/bdpt_wave.h"
#include "integrator/light_subpath_rate.h"
#include "integrator/path_wave.h"
#include "integrator/pilot.h"
#include "light/light_sampler.h"
#include "material/may_be_specular.h"
#include "math/rng.h"
#include "scene/scene.h"

namespace lantern {

namespace {
// About 512 pixels of the image at its own resolution, 64 samples each,
// with two seeds, for bdpt and for the path tracer.
constexpr double kGridPixels = 512.0;
constexpr uint32_t kGridSpp = 64;
}  // namespace

std::string why_not_eye_subpaths_alone(const Scene& scene, const RenderOptions& opt) {
  const LightPools& lights = scene.lights;
  if (opt.integrator != Integrator::Bdpt) return std::string("the integrator is ") + name(opt.integrator) + ", not bdpt";
  if (!lights.point.empty() || !lights.spot.empty() || !lights.distant.empty())
    if (const std::string kind = kind_that_may_be_specular(scene.materials, scene.textures); !kind.empty())
      return std::string("the scene has a ") +
             (!lights.point.empty()  ? "point"
              : !lights.spot.empty() ? "spot"
                                     : "distant") +
             " light and a " + kind +
             " material that may be smooth, and only light subpaths carry that light through it";
  if (opt.strategies) return "per-strategy images need light subpaths";
  if (opt.debug_unit_mis_weights) return "unit MIS weights are bdpt's own";
  if (opt.guide_light_subpaths) return "guided light subpaths (--guide-light) need light subpaths";
  if (opt.mis != MisHeuristic::Power) return "the path tracer weighs its strategies with the power heuristic, not the balance heuristic";
  return {};
}

bool may_render_eye_subpaths_alone(const Scene& scene, const RenderOptions& opt) {
  return why_not_eye_subpaths_alone(scene, opt).empty();
}

float eye_alone_weight(const StrategyRecord& r, float mis_beta) {
  if (r.s >= 2 || r.t < 2) return 0.f;
  return r.s == 0 && r.t == 2 ? 1.f : weight_at_rate(r.weight, r.rescaled, false, 0.f, mis_beta);
}

double eye_alone_density_ratio(const StrategyRecord& r) {
  // 1 / w - 1: the others' densities squared over this one's (power
  // heuristic, every count 1 at the rate the records are made at)
  const double others = std::max(0.0, 1.0 / double(r.weight) - 1.0), eye = double(r.rescaled);
  if (r.s >= 2) return 1.0 / std::sqrt(eye);                  // eye strategies' share: their densities squared
  if (r.s == 0 && r.t == 2) return 1.0;                        // the only one left
  const double kept = std::max(0.0, others - eye);             // the other eye strategy's density squared
  if (r.s == 1 && r.t == 1) return 1.0 / std::sqrt(kept);      // s = 0 alone can find the light seen from the camera
  return (1.0 + std::pow(kept, 1.5)) / ((1.0 + kept) * (1.0 + kept));
}

PilotGrid::PilotGrid(int width, int height, int stride) : width(width), height(height), stride(stride) {
  const int half = stride / 2;
  columns = (width - half + stride - 1) / stride;
  for (int y = half; y < height; y += stride)
    for (int x = half; x < width; x += stride) pixels.push_back(uint32_t(y) * uint32_t(width) + uint32_t(x));
}

int PilotGrid::grid_index(int x, int y) const {
  const int half = stride / 2;
  if (x < half || y < half || x >= width || y >= height || (x - half) % stride != 0 || (y - half) % stride != 0)
    return -1;
  return (y - half) / stride * columns + (x - half) / stride;
}

int PilotGrid::cell_index(int x, int y) const {
  if (x < 0 || y < 0 || x >= width || y >= height) return -1;
  const int rows = int(pixels.size()) / columns;
  return std::min(y / stride, rows - 1) * columns + std::min(x / stride, columns - 1);
}

EyeAloneMoments::EyeAloneMoments(int width, int height, int stride, uint32_t spp, float q, float mis_beta,
                                 bool stratified)
    : grid_(width, height, stride), spp_(spp), q_(q), beta_(mis_beta), stratified_(stratified) {
  const size_t n = grid_.pixels.size();
  bdpt_.assign(n, {0.0, 0.0});
  alone_.assign(n, {0.0, 0.0});
  light_.assign(n, {0.0, 0.0});
  coin_.assign(n, 0.0);
  value_.assign(n, 0.0);
  splat_square_.assign(n, 0.0);
  sample_sum_.assign(n, 0.0);
  sample_square_.assign(n, 0.0);
}

void EyeAloneMoments::add_bdpt(int seed, size_t first, const WaveDesc& wave, const std::vector<StrategyRecord>& records) {
  // A pixel of the grid stands for its cell of stride x stride pixels, and
  // takes the splats that land in it (the second moment a pixel of the
  // render receives from its light subpaths: the pilot traces one for each
  // of the cells' pixels' samples; `area` is the image over the cells).
  const double area =
      double(grid_.width) * double(grid_.height) / (double(grid_.pixels.size()) * grid_.stride * grid_.stride);
  std::vector<double> once(wave.size(), 0.0), with_light(wave.size(), 0.0), at_one(wave.size(), 0.0);
  for (const StrategyRecord& r : records) {
    const double u = double(average(r.unweighted)), weighted = double(average(r.weighted));
    if (!(u != 0.0) || !std::isfinite(u) || !std::isfinite(weighted)) continue;  // (as the film drops it)
    const bool needs_light_subpath = r.s >= 2;
    const double v = double(weight_at_rate(r.weight, r.rescaled, needs_light_subpath, q_, beta_)) * u;
    if (r.t == 1) {
      const int g = grid_.cell_index(int(std::floor(r.p_raster.x)), int(std::floor(r.p_raster.y)));
      if (g >= 0) {
        value_[size_t(g)] += area * weighted;
        splat_square_[size_t(g)] += area * (needs_light_subpath ? v * v / double(q_) : v * v);
      }
    } else if (r.slot < wave.size()) {
      value_[first + r.slot / wave.samples] += weighted;
      at_one[r.slot] += weighted;
      (needs_light_subpath ? with_light : once)[r.slot] += v;
    }
  }
  for (uint32_t slot = 0; slot < wave.size(); ++slot) {
    const size_t g = first + slot / wave.samples;
    bdpt_[g][size_t(seed)] += once[slot] + with_light[slot];
    light_[g][size_t(seed)] += with_light[slot];
    coin_[g] += with_light[slot] * with_light[slot];
    sample_sum_[g] += at_one[slot];
    sample_square_[g] += at_one[slot] * at_one[slot];
  }
}

void EyeAloneMoments::add_alone(int seed, const std::vector<FilmSample>& samples) {
  for (const FilmSample& f : samples) {
    const double v = double(average(f.L)) * (f.negative ? -1.0 : 1.0);
    const int g = grid_.grid_index(f.pixel);
    if (g >= 0 && std::isfinite(v)) alone_[size_t(g)][size_t(seed)] += v;  // (as the film drops it)
  }
}

std::array<double, 2> EyeAloneMoments::relative_error() const {
  const double n = double(spp_), pixels = double(grid_.pixels.size()), q = double(q_);
  double image = 0.0;
  for (const double v : value_) image += v / (2.0 * n);
  image /= pixels;
  std::array<double, 2> e{};
  if (!(image > 0.0) || !std::isfinite(image)) return e;  // a black image: nothing to choose by
  const auto pair = [n](const std::array<double, 2>& s) { return 0.5 * (s[0] - s[1]) * (s[0] - s[1]) / (n * n); };
  for (size_t g = 0; g < grid_.pixels.size(); ++g) {
    const double mean = value_[g] / (2.0 * n), scale = 1.0 / (mean * mean + image * image);
    // The variance of a pixel's mean of n samples: half the squared
    // difference of the two seeds' means; bdpt's adds its coin (the light
    // subpath's share, 1 / q - 1 times its second moment; a stratified
    // sampler traces q n of a pixel's samples, which takes its mean's share
    // out) and its splats' second moment.
    const double b = 0.5 * (light_[g][0] + light_[g][1]) / n;
    const double coin = (0.5 * coin_[g] - (stratified_ ? n * b * b : 0.0)) * (1.0 / q - 1.0) / (n * n);
    const double bdpt = pair(bdpt_[g]) + std::max(0.0, coin) + 0.5 * splat_square_[g] / (n * n);
    if (std::isfinite(bdpt)) e[0] += bdpt * scale;
    if (std::isfinite(pair(alone_[g]))) e[1] += pair(alone_[g]) * scale;
  }
  for (double& x : e) x *= n / pixels;  // (per camera sample)
  return e;
}

GridMeans EyeAloneMoments::bdpt_means() const {
  const double n = 2.0 * double(spp_);
  GridMeans m;
  m.samples = n;
  for (size_t g = 0; g < grid_.pixels.size(); ++g) {
    m.mean.push_back(value_[g] / n);
    m.variance.push_back(grid_mean_variance(sample_sum_[g], sample_square_[g], n, splat_square_[g]));
  }
  return m;
}

bool eye_subpaths_alone_pay(const EyeAloneEstimate& e, double first_ratio) {
  const double grid_ratio = e.alone_error / e.bdpt_error, agreement = first_ratio / grid_ratio;
  if (!(agreement >= 1.0 / kPilotsAgree && agreement <= kPilotsAgree)) return false;  // (also: nothing measured, or not finite)
  return e.alone_error * e.alone_cost <= kClearGain * e.bdpt_error * e.bdpt_cost;
}

int grid_pilot_stride(int width, int height) {
  return std::max(1, int(std::ceil(std::sqrt(double(width) * double(height) / kGridPixels))));
}

double grid_pilot_samples() { return 4.0 * kGridPixels * kGridSpp; }  // (two seeds, bdpt and the path tracer)

bool worth_a_grid_pilot(const BdptSettings& render) {
  return render_pays_for_pilot(render.planned_spp, render.width, render.height, grid_pilot_samples());
}

EyeAloneEstimate estimate_eye_subpaths_alone(const Scene& scene, const LightSampler& light_sampler,
                                             const BdptSettings& render, float q, const PathTracerSettings& eye_alone,
                                             RayBackend backend, bool with_alone) {
  const int width = render.full_width > 0 ? render.full_width : render.width;
  const int height = render.full_height > 0 ? render.full_height : render.height;
  const int stride = grid_pilot_stride(width, height);
  BdptSettings pilot = pilot_settings(render, width, height, kGridSpp);
  pilot.record_strategies = true;
  pilot.light_subpath_rate = 1.f;
  PathTracerSettings path = pilot_settings(eye_alone, width, height, kGridSpp);
  EyeAloneMoments moments(width, height, stride, kGridSpp, q, pilot.mis_beta, pilot.sampler.type != SamplerKind::Independent);
  WaveStats b, p;
  for (int seed = 0; seed < 2; ++seed) {
    pilot.seed = path.seed = hash_key(render.seed, 0x65796531ULL, uint64_t(seed));  // (two seeds of their own)
    const Bdpt bdpt(scene, light_sampler, pilot);
    b += trace_pilot(scene, bdpt, moments.pixels(), kGridSpp, backend,
                     [&](const WaveDesc& wave, size_t first, const WaveOutput& out) {
                       moments.add_bdpt(seed, first, wave, out.strategies);
                     });
    if (!with_alone) continue;
    const PathTracer tracer(scene, light_sampler, path);
    p += trace_pilot(scene, tracer, moments.pixels(), kGridSpp, backend,
                     [&](const WaveDesc&, size_t, const WaveOutput& out) { moments.add_alone(seed, out.samples); });
  }
  EyeAloneEstimate e;
  const std::array<double, 2> error = moments.relative_error();
  e.bdpt_error = error[0];
  e.alone_error = error[1];
  e.bdpt_means = moments.bdpt_means();
  // Rays per camera sample; bdpt's also its work that casts no ray
  // (choosing and sampling the light subpath's first vertex, joining it to
  // the camera and splatting it, the vertices' MIS sums), about one ray:
  // its time per camera sample is its rays' time and 0.6 to 1.2 of a ray
  // more, at q = 1 and q = 1/8 alike, on five shipped scenes
  // (docs/performance.md).
  const double samples = 2.0 * double(moments.pixels().size()) * kGridSpp;
  const size_t escaped = size_t(PathEnd::Escaped);
  const double eye = double(b.eye_vertices + b.eye_ends[escaped] + b.light_samples) / samples;
  const double light = double(b.light_vertices + b.light_ends[escaped] + b.light_connections) / samples;
  e.bdpt_cost = eye + 2.0 + double(q) * light;  // (1 of the 2: s = 1, t = 1's ray)
  e.alone_cost = double(p.eye_vertices + p.eye_ends[escaped] + p.light_samples) / samples;
  return e;
}

}  // namespace lantern
