#include "integrator/render_settings.h"

#include <cmath>
#include <stdexcept>
#include <string>

#include "scene/scene.h"

namespace lantern {

void check_options(const Scene& scene, const RenderOptions& opt) {
  if (uint8_t(opt.integrator) > uint8_t(Integrator::Ppm) || uint8_t(opt.mis) > uint8_t(MisHeuristic::Balance) ||
      uint8_t(opt.light_sampler) > uint8_t(LightSamplerKind::Uniform) || uint8_t(opt.ray_backend) > uint8_t(RayBackend::Packet16) ||
      uint8_t(opt.sampler.type) > uint8_t(SamplerKind::ZSobol))
    throw std::invalid_argument("an integrator, MIS heuristic, sampler, light sampler or ray back end outside its enumeration");
  const bool merging = merges_vertices(opt.integrator);
  if (merging && (!(opt.vcm_radius >= 0.f) || !std::isfinite(opt.vcm_radius) || !(opt.vcm_alpha > 0.f && opt.vcm_alpha <= 1.f)))
    throw std::invalid_argument(std::string(name(opt.integrator)) + " needs a radius >= 0 (0: automatic) and an alpha in (0, 1]");
  if (opt.spp <= 0 && opt.time_limit_seconds <= 0) throw std::invalid_argument("--spp must be positive");
  if (opt.maxdepth < 0) throw std::invalid_argument("--maxdepth must be >= 0");
  if (opt.spectral && !scene.media.rgb_grid.empty())
    throw std::invalid_argument("an \"rgbgrid\" medium is not rendered with sampled wavelengths yet (its optical depth is "
                                "integrated as colour): render it without --spectral");
  if (opt.integrator == Integrator::Lt && scene.camera.projection == Projection::Orthographic && !(scene.camera.lens_radius > 0.f))
    throw std::invalid_argument("light tracing (--integrator lt) cannot reach an orthographic camera without a lens: "
                                "its rays are parallel, so no light path connects to it; use path or bdpt, or give the "
                                "camera a \"lensradius\"");
  if (opt.strategies && opt.integrator != Integrator::Bdpt && !merging)
    throw std::invalid_argument("per-strategy images need --integrator bdpt, vcm, bpm or ppm");
  if (opt.wave_size < 1 || opt.wave_size > (1 << 22)) throw std::invalid_argument("--wave-size must lie in [1, 4194304]");
  if (opt.strategies && !opt.checkpoint_path.empty())
    throw std::invalid_argument("per-strategy images cannot be checkpointed or resumed");
  if (opt.resume && opt.checkpoint_path.empty()) throw std::invalid_argument("resume needs a checkpoint path");
  if (opt.share_count == 0 || opt.share_index >= opt.share_count)
    throw std::invalid_argument("--part K/N needs 1 <= K <= N");
  if (opt.share_count > 1 && opt.film_path.empty())
    throw std::invalid_argument("a part of a render (--part) needs a file for its film");
  if (opt.strategies && (opt.share_count > 1 || !opt.film_path.empty()))
    throw std::invalid_argument("per-strategy images cannot be rendered in parts");
  if (!opt.sampler.randomization.empty()) parse_randomization(opt.sampler.randomization);
}

BdptSettings bdpt_settings(const Scene& scene, const RenderOptions& opt, int width, int height, uint32_t planned_spp) {
  BdptSettings bs;
  const bool merging = merges_vertices(opt.integrator);
  bs.maxdepth = opt.maxdepth;
  bs.seed = opt.seed;
  bs.width = width;
  bs.height = height;
  bs.mis_beta = opt.mis == MisHeuristic::Balance ? 1.f : 2.f;
  bs.light_tracing_only = opt.integrator == Integrator::Lt;
  bs.merging = merging;
  bs.connections = !merging || opt.integrator == Integrator::Vcm;
  bs.photon_mapping = opt.integrator == Integrator::Ppm;
  bs.vcm_alpha = opt.vcm_alpha;
  bs.vcm_radius = opt.vcm_radius > 0.f                  ? opt.vcm_radius
                  : scene.settings.merge_radius > 0.f ? scene.settings.merge_radius
                                                      : 0.003f * scene.lights.scene_radius;
  bs.unit_weights = opt.debug_unit_mis_weights;
  bs.record_strategies = opt.strategies;
  bs.footprint_spp = scene.settings.spp;
  bs.sampler = opt.sampler;
  bs.planned_spp = planned_spp;
  bs.spectral = opt.spectral;
  return bs;
}

PathTracerSettings path_settings(const Scene& scene, const RenderOptions& opt, int width, int height,
                                 uint32_t planned_spp) {
  PathTracerSettings ps;
  ps.maxdepth = opt.maxdepth;
  ps.seed = opt.seed;
  ps.width = width;
  ps.height = height;
  ps.footprint_spp = scene.settings.spp;
  ps.sampler = opt.sampler;
  ps.planned_spp = planned_spp;
  ps.spectral = opt.spectral;
  return ps;
}

}  // namespace lantern
