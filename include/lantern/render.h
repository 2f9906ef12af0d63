// Rendering a loaded scene.
#pragma once

#include <array>
#include <atomic>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "lantern/image.h"
#include "lantern/options.h"
#include "lantern/scene.h"

namespace lantern {

class Timeline;  // src/trace/timeline.h
class Film;      // src/film/film.h
class UnitSet;   // src/film/unit_set.h

struct RenderProgress {
  double fraction = 0.0;  // of the sample budget, or of the time budget
  double elapsed_seconds = 0.0;
  uint64_t samples_done = 0;
  uint64_t samples_total = 0;  // the sample budget (with --time: one pass)
};

struct RenderOptions {
  Integrator integrator = Integrator::Path;
  // vcm, bpm, ppm: the merging radius of the first sample pass (0: the
  // scene's, from an "sppm" Integrator's "radius", else 0.003 of the
  // scene's bounding radius; docs/vcm.md), and
  // alpha, by which the radius of pass i is radius * i^((alpha - 1) / 2).
  float vcm_radius = 0.f;
  float vcm_alpha = 0.75f;
  MisHeuristic mis = MisHeuristic::Power;  // bdpt's
  int spp = 16;
  double time_limit_seconds = 0.0;  // > 0: render passes until the time is up (spp is then ignored)
  // > 0: adaptive sampling (integrator/adaptive_sampling.h): pixels take
  // passes until their estimated relative MSE is below this; spp (or the
  // time) is then the limit. Not with vcm, bpm, ppm, shares or MPI.
  double target_error = 0.0;
  // Adaptive sampling without a target (integrator/adaptive_sampling.h):
  // spp is then the mean over the image's pixels (32 or more), or the time
  // limit the budget, and samples go where the estimate says they pay the
  // most. Ignored with a target error. The same integrators as a target.
  bool adaptive = false;
  // Path guiding (docs/guiding.md): paths learn where light comes from
  // and sample directions from it, mixed with the BSDF. path, and the eye
  // subpaths of bdpt and vcm; not with shares or MPI.
  bool guiding = false;
  // bdpt's and vcm's light subpaths learn where what leaves a surface reaches the
  // image, and sample it (docs/guiding.md); with or without `guiding`.
  bool guide_light_subpaths = false;
  // What each guiding leaf learns directions with: the SD-tree's quadtree
  // (Müller et al. 2017) or a mixture of von Mises-Fisher lobes fitted by
  // EM (docs/guiding-lobes.md). The lobes: where guiding pays they pay
  // more, and where it does not, guide_stop ends both alike.
  GuideModel guide_distribution = GuideModel::Vmm;
  // Each guided field stops (no look-ups, no records) at the end of a
  // learning iteration whose records say it does not pay
  // (guiding/sd_tree.h, judge); false: guided to the end.
  bool guide_stop = true;
  bool any_guiding() const { return guiding || guide_light_subpaths; }
  // The path tracer's Russian roulette: from the second bounce on a path
  // goes on with probability min(1, roulette_scale x its throughput), its
  // throughput divided by that probability (unbiased for any scale > 0).
  // pbrt-v4's rule is 1; 2 keeps more of the paths whose light the image
  // still needs, and leaves less error per second on most scenes
  // (docs/performance.md, "Russian roulette that keeps more paths").
  float roulette_scale = 2.f;
  // The path tracer (and bdpt's eye subpaths alone, which it renders):
  // each camera sample's first hit shared by `split`
  // paths (1, 2, 4, 8 or 16), its camera ray, emission and next-event
  // estimate computed once, the BSDF sampled per path; spp then counts
  // paths. Pixels that see an emitter, an infinite light or a surface that
  // may be specular keep whole camera samples (docs/splitting.md). Not
  // with media or guiding, where it is 1. kSplitAuto: chosen per scene by
  // a pilot that measures 1's and 4's error at equal time, for renders
  // large enough to be worth it (integrator/split_choice.h).
  uint32_t split = kSplitAuto;
  // bdpt: the probability that a camera sample traces a light subpath
  // beyond the light, its strategies weighted for it (docs/bdpt.md, "The
  // light subpath rate"); 1 is pbrt-v4's bdpt. kLightSubpathsAuto: chosen
  // before the render by a pilot that estimates each rate's error at equal
  // time (1, 1/2, 1/4 or 1/8).
  float light_subpath_rate = kLightSubpathsAuto;
  // vcm: whether a pilot may find that merges do not pay and render as
  // bdpt (--merging auto, the default; docs/vcm.md, "Merges that pay"),
  // or merges are kept whatever they pay (--merging on).
  bool merging_pilot = true;
  int maxdepth = 5;
  int threads = 0;  // 0: all cores
  uint64_t seed = 0;
  SamplerSettings sampler;  // the app passes the scene's (or --sampler's)
  LightSamplerKind light_sampler = LightSamplerKind::Bvh;  // next-event estimation's choice of light
  // How light subpaths (bdpt, lt, vcm, bpm, ppm) choose their light: by
  // power (pbrt-v4's), uniformly over the lights that emit, or auto: for
  // bdpt with light_subpath_rate auto, the rate's pilot chooses among
  // those and two choices it measures (integrator/light_choice_pilot.h);
  // otherwise by power.
  LightChoiceKind light_choice = LightChoiceKind::Auto;
  int width = 0, height = 0;  // 0: the scene's Film resolution
  // The part of the image to render, over the Film's own "cropwindow" and
  // "pixelbounds", as pbrt-v4's --cropwindow, --pixelbounds and --pixel
  // are: crop_window [x0 x1 y0 y1] in [0, 1] when x1 >= 0 (it wins over
  // any pixel bounds), else pixel_bounds [x0 x1 y0 y1] (clamped to the
  // image) when x1 >= 0; unset, the Film's.
  std::array<float, 4> crop_window{0.f, -1.f, 0.f, -1.f};
  std::array<int, 4> pixel_bounds{0, -1, 0, -1};
  RayBackend ray_backend = RayBackend::StreamNp;
  int wave_size = 4096;  // paths per wave
  bool spectral = false;  // sample wavelengths as pbrt-v4 does (docs/spectral.md) instead of rendering in RGB
  // pbrt-v4's Film "gbuffer": the image also carries the first visible
  // surface's channels (albedo, position, depth slopes, normals, uv: camera
  // space, or the world's with gbuffer_world) from up to 64 camera samples
  // a pixel, and each pixel's sample variance (Image::channel_names). Not
  // with --part or MPI.
  bool gbuffer = false;
  bool gbuffer_world = false;
  // pbrt-v4's Film "spectral": with spectral_buckets > 0 the render is
  // spectral, its wavelengths drawn uniformly over [spectral_lambda_min,
  // spectral_lambda_max], and the image also carries that many buckets of
  // radiance ("S0.<centre>nm", docs/spectral.md). Not with --part or MPI.
  int spectral_buckets = 0;
  float spectral_lambda_min = 360.f, spectral_lambda_max = 830.f;
  bool collect_stats = false;  // time stages and ray queries (two clock reads per stage and batch)
  std::string dump_rays;       // when set: write every ray batch given to Embree to this file (perf/ replays it)
  bool strategies = false;  // bdpt: also produce one weighted and one unweighted image per (s, t)
  bool debug_unit_mis_weights = false;  // tests only: weight every bdpt strategy 1 (a deliberately biased estimator)

  // Checkpoints. With checkpoint_path set, the film's sums and the position
  // in the sample sequence are written there (atomically) every
  // checkpoint_seconds (0: never periodically) and when the render is
  // cancelled (and, for a guided render whose processes share what they
  // learn, at the end of each learning iteration); a render that completes
  // deletes the file. With resume, the
  // render first restores that file and continues where it stopped: the
  // result equals, bit for bit, a render that ran straight through. A time
  // budget counts the time of every run. Not with strategies.
  std::string checkpoint_path;
  double checkpoint_seconds = 0.0;
  bool resume = false;
  // A render that completes writes its final state to the checkpoint and
  // keeps it, so that a later run with resume and a larger spp extends it
  // (to the image a straight render of that budget makes, where the
  // samples allow: integrator/render_checkpoints.h, extension_refusal).
  bool keep_checkpoint = false;
  std::string checkpoint_key;  // identifies the scene; a checkpoint made for another key is refused
  // Several processes (MPI ranks) checkpoint one render in pieces: rank r
  // writes checkpoint_path.rank<r> (-1: one process, checkpoint_path
  // itself). Resuming reads every piece, whatever the number of ranks that
  // wrote them, in the process with resume_reads; the others learn the
  // units done from sync_checkpoint, which every process calls once before
  // rendering (the reading one passes what it read on; RenderHooks).
  int checkpoint_rank = -1;
  bool resume_reads = true;

  // Shares (--part K/N): render only the units u (one wave of one pass
  // each, numbered through the render) with u % share_count == share_index,
  // and write the film's sums and the units done to film_path at the end,
  // finished or interrupted. `lantern merge` adds such files; the sum of all
  // shares equals the whole render bit for bit (film/unit_set.h).
  uint32_t share_index = 0, share_count = 1;
  std::string film_path;
};

// What other parties add to a render, none of it needed: a progress
// report, a stop flag, a timeline, the end of each pass, and the hooks by
// which several processes (MPI ranks, src/distributed/) share one render.
// RenderOptions say what to render; these say who watches and who helps.
struct RenderHooks {
  std::function<void(const RenderProgress&)> progress;  // twice a second, from a thread of its own, and at the end
  const std::atomic<bool>* cancel = nullptr;  // set it to stop after the waves in flight
  Timeline* timeline = nullptr;  // --trace: record every wave, stage and ray query on it
  // Called from the film's merging thread when every wave of a pass has
  // been merged and before any wave of the next one is: `spp` samples per
  // pixel are in the film (of this process's share). RenderSession::snapshot
  // called from here shows exactly that pass.
  std::function<void(uint32_t spp)> pass_done;
  std::function<void()> checkpoint_written;  // after each checkpoint (from the merging thread)
  // The other processes of a checkpointed render learn the units done,
  // the time spent and what the units learnt (a guiding field's bytes)
  // from the process that read the checkpoint (RenderOptions::resume_reads)
  // through this, which every process calls once before rendering.
  std::function<void(UnitSet& done, double& elapsed_seconds, std::string& learnt)> sync_checkpoint;
  // Work handed out by another party. The units this render wants (of its
  // share, not yet in the film) form a sequence in increasing unit order;
  // next_ticket, called serially before each unit, returns the position in
  // that sequence of the next unit this process renders, increasing from
  // call to call, or UINT64_MAX to stop. It is not called once the render is
  // cancelled or out of time, so every ticket handed out is rendered.
  // Unset: every wanted unit in turn.
  std::function<uint64_t()> next_ticket;
  // Called once at the end, with the film, before the image is made from
  // it: the place to add other processes' films into it.
  std::function<void(Film&)> reduce_film;
  // Processes that render one image (MPI's ranks) make one choice where a
  // pilot or a checkpoint decides (vcm's merges, bdpt's light subpaths,
  // the path tracer's split): the process that reads the checkpoint's.
  // Every process calls it at the same points, in the same order, with its
  // own choice's bytes, and finds that process's in them after. Unset:
  // each process keeps its own.
  std::function<void(std::string& choice)> agree;
  // Processes that render one guided image (MPI's ranks) learn one field:
  // at the end of each of its learning iterations, and where one of them
  // stops inside one (an interrupt, a time budget), every process calls
  // this once with what it learnt in the iteration (`sums`: 128-bit two's
  // complement integers, little-endian, each to be added to the other
  // processes' at the same place, saturating at 2^127 - 1), whether it
  // stops (`stop`: 1, and 2 too if it was interrupted), and the passes its
  // pace predicts for a time budget (0: none). It returns the bits of
  // every process's `stop` or'ed, with `sums` the processes' totals and
  // `passes` the first process's.
  std::function<uint8_t(std::string& sums, uint8_t stop, uint64_t& passes)> share_learnt;
};

struct RenderStats {
  double seconds = 0.0;
  uint64_t samples = 0;
  uint64_t light_paths = 0;  // bdpt, lt: light subpaths traced
  uint64_t camera_rays = 0, extension_rays = 0, light_rays = 0, shadow_rays = 0;
  uint64_t nonfinite_samples = 0;  // produced NaN/Inf; counted and discarded, never on the film
  uint32_t min_spp = 0;            // samples in the least-sampled pixel
  uint32_t max_spp = 0;            // in the most-sampled one
  // With adaptive sampling: the image's relative MSE as the film's
  // half-buffers estimate it (its camera samples'); -1 otherwise.
  double estimated_relmse = -1.0;
  // With path guiding: the field's learning iterations completed, its
  // spatial leaves, directional nodes (sampled and learning) and bytes, and
  // the leaves whose paths in a medium sample a distribution learnt there;
  // the leaves of the field that guides distances in media, and those of
  // them that learnt some scattered radiance (the path tracer's).
  uint32_t guiding_iterations = 0;
  size_t guiding_leaves = 0, guiding_nodes = 0, guiding_bytes = 0, guiding_medium_leaves = 0;
  size_t guiding_distance_leaves = 0, guiding_distance_lit_leaves = 0;
  size_t guiding_light_leaves = 0;  // the importance field's (--guide-light)
  // The records this process learnt from, of the radiance field (and those
  // of them a mixture's parallax aims at the point their ray reached:
  // --guide-distribution vmm; 0 otherwise) and of the importance field.
  uint64_t guiding_records = 0, guiding_records_aimed = 0, guiding_light_records = 0;
  // Whether each field's guide paid for itself (guiding/sd_tree.h, judge):
  // the iteration it stopped after (0 first; -1: it did not stop) and the
  // share of the BSDF's second moment it left in the last iteration
  // judged (-1: none), of the radiance field and of the importance field.
  int32_t guiding_stopped_after = -1, guiding_light_stopped_after = -1;
  double guiding_share = -1.0, guiding_light_share = -1.0;

  // Subpath vertices on surfaces, and why subpaths ended (escaped, absorbed,
  // roulette, maxdepth), summed over all samples.
  uint64_t eye_vertices = 0, light_vertices = 0;
  // Next-event estimation (path; bdpt's s = 1): lights sampled, and those
  // whose sample was non-zero and unoccluded (how well lights are chosen).
  uint64_t light_samples = 0, light_samples_unoccluded = 0;
  uint64_t merges = 0;        // vcm: light vertices merged with eye vertices
  float vcm_radius = 0.f;     // vcm: the first pass's merging radius
  // bdpt: the light subpath rate rendered with (0: the eye subpaths alone;
  // -1: not bdpt); with the pilot's choice, its candidates and its
  // estimates for each: the relMSE of one camera sample per pixel, and
  // rays per camera sample.
  float light_subpath_rate = -1.f;
  std::vector<double> light_subpath_candidates, light_subpath_error, light_subpath_cost;
  // bdpt with several lights: how light subpaths chose their light (the
  // pilot's choice: "power", as pbrt-v4, or another candidate), its
  // probability per light (empty: by power), and each candidate's name,
  // estimated relMSE and MSE (over the image's mean squared) per camera
  // sample at its best rate, and rays per camera sample.
  std::string light_choice;
  std::vector<double> light_choice_probability;
  std::vector<std::string> light_choice_candidates;
  std::vector<double> light_choice_error, light_choice_mse, light_choice_cost;
  // path: the paths per camera sample rendered with (0: not the path
  // tracer); with the pilot's choice (--split auto), its candidates and
  // its estimates: each one's error at equal time relative to 1's, and the
  // share of a path's work its camera sample does once.
  uint32_t split = 0;
  std::vector<uint32_t> split_candidates;
  std::vector<double> split_error;
  double split_camera_share = 0.0;
  // vcm with --merging auto: whether its pilot kept merges (1) or had it
  // render as bdpt (0), or its checkpoint did (from_checkpoint), and the
  // pilot's estimates for vcm and for bdpt: relMSE per camera sample and
  // rays per camera sample (-1: no choice made); of bdpt's error, the
  // part from light its pilot missed; the pilots' wall seconds (bdpt's
  // included).
  int merging_pilot = -1;
  bool merging_from_checkpoint = false;
  std::array<double, 2> merging_error{}, merging_cost{};
  double merging_missed = 0.0, merging_seconds = 0.0;
  float vcm_last_radius = 0.f;  // vcm: the merging radius of the last pass traced
  uint32_t vcm_wave_paths = 0;  // vcm: each wave's light subpaths, which its eye vertices merge with
  uint32_t vcm_last_first_sample = 0;  // vcm: the first sample index of that pass
  double vcm_grid_seconds = 0.0;  // vcm, with stats: thread-seconds building the merging grids
  // mlt: the mean importance of the bootstrap samples (b), the chains, and
  // their proposals and how many were accepted. `samples` counts every
  // bidirectional sample traced: the bootstrap's, the chains' first states
  // and the proposals.
  double mlt_b = 0.0;
  uint32_t mlt_chains = 0;
  uint64_t mlt_proposals = 0, mlt_accepted = 0, mlt_traced = 0;
  std::vector<std::pair<std::string, uint64_t>> eye_ends, light_ends;
  size_t wave_pool_bytes = 0;  // structure-of-arrays pools of all threads
  int threads = 0;

  // Image textures read through the texture cache (all 0 without any).
  bool texture_cache = false;
  int64_t texture_bytes_read = 0, texture_tiles_read = 0, texture_peak_tiles = 0, texture_cache_bytes = 0;
  int64_t texture_failed_lookups = 0;  // a file unreadable during the render: read as 0
  int64_t texture_lookups = 0;
  double texture_lookup_seconds = 0.0;  // thread-seconds, with collect_stats

  // Next-event estimation's light sampler, and for "bvh" its tree.
  std::string light_sampler;
  double light_sampler_seconds = 0.0;  // build time
  size_t light_sampler_bytes = 0, light_bvh_nodes = 0;
  int light_bvh_depth = 0;

  // With RenderOptions::collect_stats: thread-seconds per stage (summed over
  // threads), in Embree queries per ray kind, and wall seconds merging waves
  // into the film (one thread).
  bool timed = false;
  std::vector<std::pair<std::string, double>> stage_seconds;
  double camera_ray_seconds = 0.0, extension_ray_seconds = 0.0, light_ray_seconds = 0.0, shadow_ray_seconds = 0.0;
  double film_seconds = 0.0;
};

// The contributions of one bidirectional strategy: s light vertices, t eye
// vertices (t = 1: light tracing). The weighted images sum to the image.
struct StrategyImage {
  int s, t;
  Image weighted, unweighted;
  bool merge = false;  // a merging strategy (vcm), whose s and t share the merged vertex
};

struct RenderResult {
  Image image;
  std::vector<StrategyImage> strategies;  // with RenderOptions::strategies
  RenderStats stats;
  bool interrupted = false;
  uint64_t resumed_samples = 0;     // samples restored from a checkpoint (included in stats.samples)
  double total_render_seconds = 0;  // this run plus the runs before a resume
};

// One render of a scene, which the command line, MPI ranks and a viewer
// drive alike: run() renders on the calling thread to the end of the budget
// (or a cancel); start() does the same on a thread of the session's, while
// the caller watches the image grow (snapshot, progress) or stops it
// (cancel). One pipeline runs over all passes either way, so watching
// costs the render nothing but the snapshots taken.
class RenderSession {
 public:
  // Throws std::invalid_argument for bad options. The scene must outlive
  // the session.
  RenderSession(const Scene& scene, RenderOptions options, RenderHooks hooks = {});
  ~RenderSession();  // cancels a started render and waits for it
  RenderSession(const RenderSession&) = delete;
  RenderSession& operator=(const RenderSession&) = delete;

  RenderResult run();   // once per session
  void start();         // run() on the session's thread
  RenderResult wait();  // after start(): its result (rethrows what it threw)
  // After start(): whether the render has ended, waiting at most `seconds`
  // for it (a caller that must stay responsive, such as Python's signal
  // checks, waits in slices; wait() then returns at once).
  bool wait_for(double seconds);
  void cancel();        // stop after the waves in flight (a signal handler may call it)

  // The image of every wave merged so far: the film resolved under its lock
  // (empty until the render has begun).
  Image snapshot() const;
  RenderProgress progress() const;
  int width() const;
  int height() const;

 private:
  RenderResult render_all();
  struct State;
  std::unique_ptr<State> state_;
};

// A whole render on the calling thread: RenderSession(...).run().
RenderResult render(const Scene& scene, const RenderOptions& options, const RenderHooks& hooks = {});

}  // namespace lantern
