// Bidirectional path tracing (Veach 1997; Lafortune & Willems 1993) with all
// strategies weighted by MIS in its recursive form (integrator/bdpt_mis.h),
// run as wavefront stages over structure-of-arrays pools. With
// light_tracing_only it is a pure light tracer (t = 1 strategies only,
// unweighted): a cross-check for the other integrators.
//
// Per wave: (1) light subpaths: emission, then bounce by bounce a surface
// stage and a shade stage that, with each vertex's BSDF built once,
// stores connectible vertices, prepares the t = 1 camera connections and
// samples the next direction, and one occlusion stream; (2) the light
// vertices are grouped by slot; (3) eye subpaths: camera rays, then bounce
// by bounce a surface stage (s = 0 emission) and a shade stage that
// prepares the s = 1 and s >= 2 connections and samples the next
// direction, and one occlusion stream. Each connection strategy is written
// once, for surface and medium vertices alike (bdpt_strategies.h).
#pragma once

#include <memory>

#include "accel/ray_stream.h"
#include "camera/camera.h"
#include "film/film.h"
#include "integrator/bdpt_mis.h"
#include "integrator/guiding_field.h"
#include "integrator/vertex.h"
#include "integrator/wave.h"
#include "integrator/wave_stats.h"
#include "integrator/wavelengths.h"
#include "lantern/options.h"
#include "light/light_sampler.h"
#include "sampler/sampler.h"
#include "scene/scene.h"
#include "texture/footprint.h"

namespace lantern {

struct BdptSettings {
  int maxdepth = 5;
  uint64_t seed = 0;
  int width = 0, height = 0;  // of the film: the pixels rendered
  // The camera's whole image, of which the film is the part from
  // raster_offset on (pbrt-v4's Film "cropwindow", "pixelbounds"); 0: the
  // film's size.
  int full_width = 0, full_height = 0;
  Vec2 raster_offset{0.f};
  float mis_beta = 2.f;             // 2: power heuristic, 1: balance heuristic
  bool light_tracing_only = false;  // the `lt` integrator
  // The light subpath rate q: the probability that a camera sample traces
  // its light subpath beyond the light (bdpt_mis.h). Below 1, a camera
  // sample without one is a path-traced sample (s = 0 and s = 1, t = 1
  // only), and one with one divides what its strategies s >= 2 bring by q.
  float light_subpath_rate = 1.f;
  // How light subpaths choose their light: a weight per light
  // (LightPools::all), or empty: by power (LightPools::selection), as
  // pbrt-v4's do. The light subpath rate's pilot may choose other weights
  // (light_subpath_rate.h).
  std::vector<float> light_choice;
  // Russian roulette of eye subpaths, scaled as the path tracer's
  // (vertex.h): 1 (pbrt-v4's rule) but in the pilot that stands in for the
  // path tracer (light_subpath_rate.h).
  float eye_roulette_scale = 1.f;
  // Vertex connection and merging (the `vcm` integrator; docs/vcm.md):
  // light vertices within the radius of an eye vertex are merged with it,
  // as further strategies. The radius of sample pass i (counting from 1)
  // is radius * i^((alpha - 1) / 2).
  bool merging = false;
  float vcm_radius = 0.f, vcm_alpha = 0.75f;
  // Without connections (the `bpm` and `ppm` integrators, with merging),
  // merges are the only strategies besides emission seen along a purely
  // specular eye subpath.
  bool connections = true;
  // Progressive photon mapping (the `ppm` integrator, without
  // connections): eye subpaths go through specular vertices only and
  // merge, unweighted, at the first other one.
  bool photon_mapping = false;
  bool unit_weights = false;        // every strategy weighted 1: deliberately wrong, for tests only
  bool record_strategies = false;   // per-(s, t) contributions into WaveOutput::strategies
  // The samples per pixel the texture filter footprint is scaled for: the
  // scene's own, so that an image does not depend on --spp or --time.
  int footprint_spp = 16;
  SamplerSettings sampler;
  uint32_t planned_spp = 0;  // 0 under a time budget
  bool spectral = false;  // sampled wavelengths instead of RGB
  WavelengthRange wavelengths;  // Film "spectral"'s uniform range (wavelengths.h)
};

struct BdptWave;
struct Connection;
struct LightOriginPool;
struct LightVertexPool;
struct SubpathPool;

// What a stored light vertex (surface or medium) does with light arriving
// from direction -wi_w (wi_w points from the eye vertex to it): e in its
// own subpath's transport (importance), so e.pdf_fwd is its density of
// sampling the direction to the eye vertex and e.pdf_rev that of its own
// subpath's previous direction from there.
struct LightVertexResponse {
  VertexEval e;
  float cos = 1.f;    // solid angle to area at it (1 in a medium)
  Spectrum sigma_t{0.f};   // extinction there (zero on a surface)
  Vec3 target{0.f};   // where a connection ray aims
};

// Occlusion queries are flushed when this many connections are waiting, so
// memory stays bounded however long the subpaths get.
inline constexpr uint32_t kMaxPendingConnections = 1u << 16;

// vcm: merges weigh against the other strategies as if merged with at most
// this many light subpaths (eta = pi r^2 min(n, this)), however many their
// wave holds; each merge's estimate divides by the true n. The weights
// stay a partition of unity either way, so a wave of more light subpaths
// lowers the merges' variance without giving their blur (the radius'
// bias) more weight than the default wave size does (docs/vcm.md).
inline constexpr uint32_t kMergeWeightPaths = uint32_t(kMergingWaveSize);

class Bdpt {
 public:
  Bdpt(const Scene& scene, const LightSampler& light_sampler, const BdptSettings& settings);

  WavePools<BdptWave> make_wave_state(uint32_t capacity, RayStream stream) const;
  void trace(const WaveDesc& wave, BdptWave& state, WaveOutput& out) const;
  // Path guiding (docs/guiding.md): eye subpaths sample the field's
  // mixture with the BSDF at surface vertices and, while it learns, leave
  // records of what they gathered. If the field guides light subpaths
  // (bdpt and vcm), their surface vertices do the same with its importance
  // field, learning from what the strategies beyond each vertex brought.
  void set_guiding(const GuidingField* field) { guiding_ = field; }

 private:
  // light subpaths (bdpt_light.cpp)
  void start_light_subpaths(const WaveDesc& wave, BdptWave& w) const;
  void start_volume_subpaths(BdptWave& w) const;
  // mix_pdf_dir: the density es.d was drawn with, where a guide drew it
  // (MIS keeps es.pdf_dir); negative: es.pdf_dir; 0: the subpath ends at
  // its first point (its s = 1, t = 1 strategy still counts).
  void begin_light_subpath(BdptWave& w, uint32_t slot, const struct EmissionSample& es, MediumHandle medium,
                           const Spectrum& sigma_origin, float mix_pdf_dir = -1.f) const;
  void light_surface_stage(BdptWave& w) const;
  void light_shade_stage(BdptWave& w) const;
  void splat_stage(BdptWave& w) const;
  void group_light_vertices(BdptWave& w) const;
  // eye subpaths (bdpt.cpp)
  void start_eye_subpaths(const WaveDesc& wave, BdptWave& w) const;
  // Metropolis (WaveDesc::chains): camera samples anywhere on the image, recorded as splats
  Vec2 metropolis_raster(Vec2 u) const;
  void metropolis_samples(const WaveDesc& wave, BdptWave& w, WaveOutput& out) const;
  void eye_surface_stage(BdptWave& w) const;
  void eye_shade_stage(BdptWave& w) const;
  void connection_stage(BdptWave& w) const;
  // Traces the pending connections and adds what they carry.
  void flush_connections(BdptWave& w) const;
  // participating media (bdpt_media.cpp)
  void segment_stage(BdptWave& w, RayKind kind, bool light_subpaths) const;
  bool apply_segment(BdptWave& w, SubpathPool& sub, uint32_t i) const;
  LightVertexResponse light_vertex_response(const LightVertexPool& v, uint32_t j, const Vec3& wi_w) const;
  // The connection strategies, each once for either kind of vertex (bdpt_strategies.h)
  template <class Vertex>  // s = 1
  void next_event(BdptWave& w, uint32_t slot, const Vertex& v, LazyNumber u_light, Vec2 u_light2) const;
  template <class Vertex>  // s >= 2
  void connect_light_vertices(BdptWave& w, uint32_t slot, const Vertex& v) const;
  template <class Vertex>  // t = 1
  void connect_camera(BdptWave& w, uint32_t slot, uint32_t ld, const Vertex& v, Vec2 u_lens) const;
  // Weights a connection now (vacuum) or queues it for its transmittance.
  void push_connection(BdptWave& w, uint32_t slot, const Connection& k) const;
  template <class Vertex>  // merges (vcm, bpm, ppm)
  void merge_at_eye_vertex(BdptWave& w, uint32_t slot, const Vertex& v) const;
  void prepare_merging(const WaveDesc& wave, BdptWave& w) const;
  MediumVertex medium_vertex(const BdptWave& w, uint32_t i) const;  // ray i's scattering point
  PathEnd scatter_in_medium(BdptWave& w, SubpathPool& sub, uint32_t i, Vec2 u2, LazyNumber u_rr, bool light,
                            const GuideAt& guide = {}, float uc = 0.f, ScatterSample* drawn = nullptr) const;
  void eye_medium_stage(BdptWave& w) const;
  void light_medium_stage(BdptWave& w) const;
  void light_medium_arrival(BdptWave& w, uint32_t i) const;
  void trace_connections(BdptWave& w) const;
  void add_escaped_emission(BdptWave& w, uint32_t slot, const Vec3& d) const;
  // rescaled: the part of its weight's ratio sum that the light subpath rate rescales
  // light: the light found (LightPools::all), for recorded strategies.
  void add_emission(BdptWave& w, uint32_t slot, const Spectrum& unweighted, float weight, float rescaled,
                    uint32_t light) const;
  // A ray of slot's light subpath (an extension or a connection of
  // s >= 2), counted by its light when strategies are recorded.
  void count_light_ray(BdptWave& w, uint32_t slot) const;
  void add_volume_emission(BdptWave& w, uint32_t i, const Spectrum& beta_before) const;
  float volume_number(const BdptWave& w, uint32_t slot) const;
  struct VolumeSampleEnd {
    MediumHandle medium;  // vacuum: not a volume light's sample
    Spectrum sigma_t{0.f};
  };
  void complete_volume_light_sample(LightSample& ls, uint32_t depth, const SampledWavelengths& lambda, VolumeSampleEnd* end) const;

  // Whether a light vertex at path depth ld is stored for the eye
  // subpaths, on a surface or in a medium alike: s >= 2 connections need
  // t >= 2, merging (vcm, bpm, ppm) t >= 1.
  bool keeps_light_vertex(uint32_t ld) const {
    const uint32_t maxdepth = uint32_t(settings_.maxdepth);
    return !settings_.light_tracing_only && (ld < maxdepth || (settings_.merging && ld <= maxdepth));
  }
  // Whether connections are weighted (not lt, whose t = 1 strategies are
  // all there is, nor the unit weights of tests; ppm makes none).
  bool weighted() const { return !settings_.light_tracing_only && !settings_.unit_weights && !settings_.photon_mapping; }
  // (ppm has one strategy per path: every weight is 1)
  float weight(float w) const { return settings_.unit_weights || settings_.photon_mapping ? 1.f : w; }
  // How a vertex in a medium merges: in a ball with vcm and bpm; ppm
  // merges on surfaces only.
  MergeKind medium_merging() const {
    return settings_.merging && !settings_.photon_mapping ? MergeKind::Medium : MergeKind::None;
  }
  MergeKind light_vertex_merging(const LightVertexPool& v, uint32_t j) const;
  // s = 0's weight, for eye subpath state m (found before the weight w)
  float emission_weight(const MisState& m, float w) const {
    return settings_.connections ? weight(w) : mis_weight_hit_light_merging_only(m);
  }

  float first_hit_direct_pdf(const LightOriginPool& o, uint32_t slot, const Vec3& p, const Vec3& ns,
                             const Vec3& p_light) const;

  // Guided light subpaths (bdpt_light_guide.cpp)
  bool guides_light() const { return guiding_ && guiding_->guides_light_subpaths(); }
  bool guides_eye() const { return guiding_ && guiding_->guides_eye_subpaths(); }
  bool learns_light() const { return guides_light() && guiding_->learning(); }
  void prepare_light_learning(BdptWave& w, uint32_t slots) const;
  // A contribution of slot's strategy with s light vertices, as it reaches the image.
  static void gather_for_light_guide(BdptWave& w, uint32_t slot, uint32_t s, const Spectrum& c);
  // An area light's emission direction by the one-sample mixture of its
  // own distribution and the importance field at its point, and the
  // mixture's density; 0 where the subpath must end at its first point
  // (only the guide could draw the direction).
  void guide_emission(BdptWave& w, uint32_t slot, struct EmissionSample& es, LazyNumber u_select, Vec2 u_pos,
                      Vec2 u_dir, float* mix_pdf_dir) const;
  void make_light_guide_records(const WaveDesc& wave, BdptWave& w, WaveOutput& out) const;

  const Scene& scene_;
  const LightSampler& light_sampler_;  // next-event estimation's (s = 1) choice of light
  Distribution1D emission_choice_;     // light subpaths' choice of light (BdptSettings::light_choice)
  BdptSettings settings_;
  Camera camera_;
  FootprintModel footprints_;  // enabled when the scene's textures filter
  MisPower mis_;
  SamplerSpec sampler_;
  SamplerSpec light_start_;  // the numbers of a light subpath's first point (make_light_start_spec)
  const GuidingField* guiding_ = nullptr;
};

}  // namespace lantern
