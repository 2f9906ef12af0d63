// Unidirectional path tracing with next-event estimation and MIS (power
// heuristic), run as wavefront stages over structure-of-arrays path state.
#pragma once

#include <memory>

#include "accel/ray_stream.h"
#include "film/film.h"
#include "integrator/guided_scatter.h"
#include "integrator/guiding_field.h"
#include "integrator/wave.h"
#include "integrator/wavelengths.h"
#include "light/light_sampler.h"
#include "sampler/sampler.h"
#include "scene/scene.h"
#include "texture/footprint.h"

namespace lantern {

struct PathTracerSettings {
  int maxdepth = 5;
  uint64_t seed = 0;
  int width = 0, height = 0;  // of the film: the pixels rendered
  // The camera's whole image, of which the film is the part from
  // raster_offset on (pbrt-v4's Film "cropwindow", "pixelbounds"); 0: the
  // film's size.
  int full_width = 0, full_height = 0;
  Vec2 raster_offset{0.f};
  // The samples per pixel the texture filter footprint is scaled for: the
  // scene's own, so that an image does not depend on --spp or --time.
  int footprint_spp = 16;
  SamplerSettings sampler;
  uint32_t planned_spp = 0;  // 0 under a time budget
  bool spectral = false;     // sampled wavelengths instead of RGB
  WavelengthRange wavelengths;  // Film "spectral"'s uniform range (wavelengths.h)
  // pbrt-v3's directlighting: a path ends at the first surface or medium
  // event after a non-specular bounce, where only emission counts
  // (Integrator::Direct).
  bool direct_lighting = false;
  // Russian roulette keeps a path with probability min(1, roulette_scale x
  // its throughput) from the second bounce on (RenderOptions::roulette_scale).
  float roulette_scale = 2.f;
  // Each camera sample's first hit is shared by `split` paths (a power of
  // two up to 16): its camera ray, emission and next-event estimation are
  // computed once, its BSDF sampled once per path (docs/splitting.md).
  // A sample index then counts paths: samples i to i + split - 1 of a
  // pixel (aligned) are one camera sample's. 1 in scenes with media,
  // ambient occlusion and directlighting, and for guided paths until their
  // field has learnt (split_camera_samples).
  uint32_t split = 1;
  RayBackend ray_backend = RayBackend::StreamNp;  // of the rays that find the pixels to split
  // Which pixels may be split: those at (s/2 + i s, s/2 + j s) for a probe
  // stride s (a pilot's: integrator/split_choice.h); 1: all of them.
  uint32_t probe_stride = 1;
  // pbrt-v4's ambientocclusion (Integrator::AmbientOcclusion): one
  // occlusion ray at the first hit, nothing else.
  bool ambient_occlusion = false;
  float ao_max_distance = kInfinity;
  bool ao_cos_sample = true;
};

struct PathWave;  // the SoA pools, reused wave after wave by one thread

// What each pixel's camera samples see first, averaged as pbrt-v4's
// GBufferFilm averages it: the albedo over every sample; the position,
// depth slopes and uv over the samples that hit a surface; the normals
// summed and normalised.
struct VisibleSurfaces {
  enum Channel { AlbedoR, AlbedoG, AlbedoB, PX, PY, PZ, DzDx, DzDy, NX, NY, NZ, NsX, NsY, NsZ, U, V, kChannels };
  int width = 0, height = 0;
  std::vector<float> values;  // kChannels per pixel, row 0 at the top
};
// Appends pbrt-v4's gbuffer channels to a resolved image of the film: the
// visible surfaces', then Variance and RelativeVariance of the film's
// camera samples (the film must track moments).
void add_gbuffer_channels(const VisibleSurfaces& v, const Film& film, Image* image);

class PathTracer {
 public:
  PathTracer(const Scene& scene, const LightSampler& light_sampler, const PathTracerSettings& settings);

  WavePools<PathWave> make_wave_state(uint32_t capacity, RayStream stream) const;
  // Traces all paths of the wave and records one sample per slot; the wave
  // state's stats and ray stream keep the measurements.
  void trace(const WaveDesc& wave, PathWave& state, WaveOutput& out) const;
  // pbrt-v4's gbuffer channels (integrator/visible_surfaces.cpp): for each
  // pixel of the film, what the first surface `samples` camera samples see
  // there shows, per VisibleSurfaces::Channel, in camera space (pbrt's, of
  // the Camera directive's transformation) or in the world.
  VisibleSurfaces visible_surfaces(uint32_t samples, bool world_space, RayBackend backend) const;

  // Path guiding (integrator/guiding_field.h): paths sample the field where
  // it has learnt something and record into it while it learns. The
  // renderer changes the field only between waves.
  void set_guiding(const GuidingField* field) { guiding_ = field; }
  // Splits the camera samples of the waves traced from now on in `split`
  // paths (PathTracerSettings::split; 1: whole), as the constructor does
  // with the settings': a guided render's, once its field has learnt
  // (integrator/pass_layout.h).
  void split_camera_samples(uint32_t split);
  // Whether the camera samples of a pixel of the film are split
  // (split_pixels.cpp).
  bool splits_pixel(uint32_t pixel) const {
    if (split_pixels_.empty()) return false;
    if (settings_.probe_stride == 1) return split_pixels_[pixel] != 0;
    const uint32_t s = settings_.probe_stride, x = pixel % uint32_t(settings_.width),
                   y = pixel / uint32_t(settings_.width);
    if (x % s != s / 2 || y % s != s / 2) return false;
    return split_pixels_[size_t(y / s) * probe_columns() + x / s] != 0;
  }

 private:
  void generate_camera_rays(const WaveDesc& wave, PathWave& w) const;
  void follow_camera_sample(PathWave& w, uint32_t slot, uint32_t leader, const PathSampler& s) const;
  void branch_first_hits(PathWave& w) const;
  std::vector<uint8_t> find_split_pixels(RayBackend backend) const;  // split_pixels.cpp
  std::vector<uint8_t> probe_pixels(const std::vector<uint32_t>& pixels, RayBackend backend) const;
  void share_first_hit_light(PathWave& w) const;
  void surface_stage(PathWave& w) const;
  void shade_stage(PathWave& w) const;
  void shadow_stage(PathWave& w) const;
  void occlusion_ray(PathWave& w, uint32_t slot, const SurfacePoint& sp, const Vec3& d) const;
  // Media are traced except by ambient occlusion, which sees only surfaces.
  bool traces_media() const { return !scene_.media.empty() && !settings_.ambient_occlusion; }
  // Participating media (path_media.cpp).
  void segment_stage(PathWave& w, RayKind kind) const;
  void medium_scatter_stage(PathWave& w) const;
  void media_shadow_stage(PathWave& w) const;
  float volume_number(const PathWave& w, uint32_t slot) const;
  void add_volume_emission(PathWave& w, uint32_t i, const Spectrum& beta_before, float prev_pdf) const;

  const Scene& scene_;
  const LightSampler& light_sampler_;  // next-event estimation's choice of light
  PathTracerSettings settings_;
  Camera camera_;
  FootprintModel footprints_;  // enabled when the scene's textures filter
  SamplerSpec sampler_;
  SamplerSpec camera_sampler_;  // of the camera samples, when they are split
  uint32_t split_log2_ = 0;
  // Per probed pixel of the film, row by row: 1 where its camera samples
  // are split.
  std::vector<uint8_t> split_pixels_;
  size_t probe_columns() const {
    const uint32_t s = settings_.probe_stride;
    return (uint32_t(settings_.width) + s - 1 - s / 2) / s;
  }
  size_t probe_rows() const {
    const uint32_t s = settings_.probe_stride;
    return (uint32_t(settings_.height) + s - 1 - s / 2) / s;
  }
  // Whether directions are guided: a field, whose guide has not stopped
  // where it does not pay (guided distances go on: distance_field()).
  bool guides() const { return guiding_ && guiding_->guides_eye_subpaths(); }
  const GuidingField* guiding_ = nullptr;
};

}  // namespace lantern
