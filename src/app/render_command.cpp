#include "app/render_command.h"

#include <nlohmann/json.hpp>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <cctype>
#include <filesystem>
#include <fstream>
#include <optional>

#include "app/cli_checks.h"
#include "app/command_line.h"
#include "app/log.h"
#include "app/outputs.h"
#include "app/render_watch.h"
#include "app/stats_report.h"
#include "film/checkpoint.h"
#include "imageio/replace_file.h"
#include "integrator/render_settings.h"
#include "lantern/render.h"
#include "lantern/scene.h"
#include "trace/timeline.h"
#ifdef LANTERN_HAVE_MPI
#include "distributed/mpi_render.h"
#endif

namespace lantern {

namespace {

std::atomic<bool> g_cancel{false};

extern "C" void on_signal(int) {
  g_cancel.store(true);
  std::signal(SIGINT, SIG_DFL);  // a second Ctrl-C ends at once
  std::signal(SIGTERM, SIG_DFL);
}

std::string hms(double s) {
  int t = int(s + 0.5);
  char buf[32];
  if (t >= 3600) std::snprintf(buf, sizeof buf, "%d:%02d:%02d", t / 3600, t / 60 % 60, t % 60);
  else std::snprintf(buf, sizeof buf, "%02d:%02d", t / 60, t % 60);
  return buf;
}

void write_strategy_images(const std::string& dir, const std::vector<StrategyImage>& images, const ImageMetadata& md) {
  std::filesystem::create_directories(dir);
  for (const StrategyImage& im : images) {
    std::string base = dir + (im.merge ? "/merge_s" : "/s") + std::to_string(im.s) + "_t" + std::to_string(im.t);
    write_image(base + "_weighted.exr", im.weighted, md);
    write_image(base + "_unweighted.exr", im.unweighted, md);
  }
}

// Written to a temporary name and moved into place, like the images
// (imageio/replace_file.h); "-" is standard output.
void write_text_atomically(const std::string& path, const std::string& text) {
  if (path == "-") {
    std::fwrite(text.data(), 1, text.size(), stdout);
    if (std::fflush(stdout) != 0) throw std::runtime_error("cannot write to standard output");
    return;
  }
  std::string tmp = temporary_output(path, "");
  {
    std::ofstream f(tmp, std::ios::binary);
    f << text;
    if (!f.flush()) throw std::runtime_error("cannot write " + tmp);
  }
  place_output(tmp, path);
}

// Loading as spans on the timeline's main track: the whole load, and each
// stage the loader reports (parsing, reading PLY meshes, building the BVH).
class LoadTrace {
 public:
  explicit LoadTrace(Timeline* t) : timeline_(t), begin_(TraceClock::now()), stage_begin_(begin_) {}
  void stage(const std::string& name) {
    if (!timeline_) return;
    close_stage();
    stage_ = timeline_->intern(name);
  }
  void done() {
    if (!timeline_) return;
    close_stage();
    timeline_->main().span("load", TraceCategory::Load, begin_, TraceClock::now());
  }

 private:
  void close_stage() {
    const auto now = TraceClock::now();
    timeline_->main().span(stage_, TraceCategory::Load, stage_begin_, now);
    stage_begin_ = now;
  }
  Timeline* timeline_;
  TraceClock::time_point begin_, stage_begin_;
  const char* stage_ = "parse";
};

struct Loaded {
  std::shared_ptr<Scene> scene;
  double seconds = 0.0;
  std::vector<LoadPhase> phases;  // each stage's end (the last: "done")
};

// The scene, with the loader's stages as a progress line (info, on a
// terminal), as lines with their times (verbose), and on the timeline.
Loaded load(const RenderArgs& a, Timeline* timeline, bool reports) {
  LoadOptions lo;
  lo.texture_cache_mb = a.texture_cache_mb;
  lo.texture_directory = a.texture_dir;
  lo.lenient = a.lenient;
  lo.memory_layout = parse_memory_layout(a.memory_layout);
  lo.threads = a.req.threads;
  lo.warn = [](const std::string& w) { logging::line(logging::Level::Warning, w); };
  LoadTrace trace(timeline);
  const auto t0 = std::chrono::steady_clock::now();
  auto elapsed = [t0] { return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(); };
  const bool in_place = reports && logging::terminal() && logging::enabled(logging::Level::Info);
  const bool lines = reports && logging::enabled(logging::Level::Verbose);
  Loaded l;
  auto phase_ends = [&] {
    if (l.phases.empty()) return;
    LoadPhase& p = l.phases.back();
    p.end_seconds = elapsed();
    p.rss_bytes = rss_bytes();
    p.peak_rss_bytes = peak_rss_bytes();
  };
  lo.progress = [&](const std::string& stage) {
    phase_ends();
    l.phases.push_back({stage});
    if (in_place || lines || timeline) {
      trace.stage(stage);
      char buf[64];
      std::snprintf(buf, sizeof buf, "[load %6.1f s] ", elapsed());
      if (lines) logging::verbose("%s%s", buf, stage.c_str());
      else if (in_place) logging::progress(buf + stage);
    }
  };
  // Included files: how far parsing has got, on the progress line, and at
  // most once a second as a verbose line (a production scene has hundreds).
  size_t files = 0, bytes = 0;
  double last_line = -1.0;
  if (in_place || lines)
    lo.file_progress = [&](const std::string& path, size_t size) {
      ++files, bytes += size;
      char buf[160];
      std::snprintf(buf, sizeof buf, "[load %6.1f s] parsing: %zu included files, %.1f MB; ", elapsed(), files,
                    double(bytes) * 1e-6);
      if (lines && elapsed() - last_line >= 1.0) {
        last_line = elapsed();
        logging::verbose("%s%s", buf, printable(path, 100).c_str());
      } else if (in_place) {
        logging::progress(buf + printable(path, 60));
      }
    };
  l.scene = load_scene(a.scene, lo);
  phase_ends();
  trace.done();
  l.seconds = elapsed();
  if (in_place && !lines) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "[load %6.1f s] done", l.seconds);
    logging::progress(buf);
    logging::end_progress();
  }
  if (reports) {
    const SceneInfo si = scene_info(*l.scene);
    logging::verbose("%s: loaded in %.2f s: %zu triangles, %zu spheres, %zu lights, %zu instances (%zu triangles traced); "
                 "BVH %.2f s, %.1f MB; geometry %.1f MB",
                 a.scene.c_str(), l.seconds, si.triangles, si.spheres, si.lights, si.instances, si.instanced_triangles,
                 si.bvh_build_seconds, double(si.bvh_bytes) * 1e-6, double(si.geometry_bytes) * 1e-6);
  }
  return l;
}

// On a terminal, a line rewritten in place. Otherwise (a batch job's log,
// mpirun's pipes, --log-file) a whole line every --progress-interval seconds.
std::function<void(const RenderProgress&)> progress_line(double interval, double pixels) {
  const bool tty = logging::terminal();
  if (!logging::enabled(logging::Level::Info) || (!tty && !(interval > 0))) return nullptr;
  return [tty, interval, pixels, last = -1e9](const RenderProgress& p) mutable {
    if (!tty && p.elapsed_seconds - last < interval && p.fraction < 1.0) return;
    last = p.elapsed_seconds;
    const double eta = p.fraction > 0 ? p.elapsed_seconds * (1.0 - p.fraction) / p.fraction : 0.0;
    const double rate = p.elapsed_seconds > 0 ? double(p.samples_done) / p.elapsed_seconds : 0.0;
    char buf[160];
    std::snprintf(buf, sizeof buf, "[%5.1f%%] %s elapsed, ETA %s, %.1f spp, %.2f Msamples/s", 100.0 * p.fraction,
                  hms(p.elapsed_seconds).c_str(), hms(eta).c_str(), double(p.samples_done) / std::max(pixels, 1.0),
                  rate * 1e-6);
    logging::progress(buf);
  };
}

// A part's render has written its file (render() does, finished or not).
int finish_part(const RenderArgs& a, const RenderOptions& o, const RenderResult& r, Timeline* timeline) {
  if (timeline) write_text_atomically(a.trace, timeline->json());
  logging::info("%s: part %s, %llu samples, %.2f s render", o.film_path.c_str(), a.part.c_str(),
            (unsigned long long)r.stats.samples, r.stats.seconds);
  if (r.interrupted) {
    logging::line(logging::Level::Error, "interrupted: " + o.film_path +
                                     " holds the part so far (merge it with --preview, or finish it with --checkpoint "
                                     "and --resume)");
    return 130;
  }
  return 0;
}

#ifdef LANTERN_HAVE_MPI
nlohmann::json rank_report_json(const std::vector<MpiRender::RankReport>& reports) {
  nlohmann::json ranks = nlohmann::json::array();
  for (const auto& r : reports)
    ranks.push_back({{"units", r.units},
                     {"samples", r.samples},
                     {"samples_per_second", r.render_seconds > 0 ? r.samples / r.render_seconds : 0.0},
                     {"render_seconds", r.render_seconds},
                     {"idle_seconds", r.ticket_seconds + r.end_wait_seconds},
                     {"ticket_wait_seconds", r.ticket_seconds},
                     {"end_wait_seconds", r.end_wait_seconds},
                     {"communication_seconds", r.reduce_seconds},
                     {"rays", r.rays[0] + r.rays[1] + r.rays[2] + r.rays[3]},
                     {"communication_bytes", r.reduce_bytes}});
  return {{"ranks", reports.size()}, {"per_rank", ranks}};
}
#endif

// The summary line (info) and what else a finished render has to say.
void report(const std::string& out, const RenderOptions& o, const RenderResult& r, double load_s) {
  const RenderStats& s = r.stats;
  const double rays = double(s.camera_rays + s.extension_rays + s.light_rays + s.shadow_rays);
  // mlt's samples per pixel are its chains' proposals (RenderStats::samples
  // counts its bootstrap's too).
  const bool mlt = s.mlt_chains > 0;
  const double pixels = double(r.image.width) * double(r.image.height);
  const uint32_t spp = mlt ? uint32_t(double(s.mlt_proposals) / pixels) : s.min_spp;
  const double samples = double(s.samples - r.resumed_samples);
  if (mlt)
    logging::info("mlt: %u chains, %.1f proposals a pixel, %.1f%% accepted; mean importance b = %.6g", s.mlt_chains,
                  double(s.mlt_proposals) / pixels,
                  s.mlt_proposals ? 100.0 * double(s.mlt_accepted) / double(s.mlt_proposals) : 0.0, s.mlt_b);
  logging::info("%s: %dx%d, %u spp (min), %.2f s render, %.2f s load; %.3f Msamples/s, %.2f Mrays/s "
            "(camera %.1fM, eye extension %.1fM, light extension %.1fM, shadow/connection %.1fM); "
            "non-finite samples discarded: %llu",
            out.c_str(), r.image.width, r.image.height, spp, s.seconds, load_s, samples / s.seconds * 1e-6,
            rays / s.seconds * 1e-6,
            double(s.camera_rays) * 1e-6, double(s.extension_rays) * 1e-6, double(s.light_rays) * 1e-6,
            double(s.shadow_rays) * 1e-6, (unsigned long long)s.nonfinite_samples);
  if (r.image.width == 1 && r.image.height == 1 && !r.image.rgb.empty())  // --pixel: its value
    logging::info("pixel value: %.9g %.9g %.9g", r.image.rgb[0], r.image.rgb[1], r.image.rgb[2]);
  if (s.estimated_relmse >= 0)
    logging::info("adaptive sampling: %u to %u spp, %.1f on average; estimated relative MSE %.3g%s", s.min_spp,
              s.max_spp, double(s.samples) / (double(r.image.width) * double(r.image.height)), s.estimated_relmse,
              o.target_error > 0 ? (" (target " + std::to_string(o.target_error) + ")").c_str() : "");
  if (!s.split_error.empty())
    logging::info("split: %u paths per camera sample, the pilot's choice (--split auto)", s.split);
  if (s.merging_pilot >= 0)
    logging::info("vcm: %s (%s, --merging auto)",
                  s.merging_pilot == 0 ? "rendered as bdpt, without merges" : "merges kept",
                  s.merging_from_checkpoint ? "as its checkpoint was made" : "the pilot's choice");
  if (!s.light_subpath_error.empty())
    logging::info("light subpaths: %g per camera sample, the pilot's choice (--light-subpaths auto)%s",
                  double(s.light_subpath_rate),
                  s.light_subpath_rate == 0.f ? ": they do not pay here, the path tracer rendered the eye subpaths alone" : "");
  else if (s.light_subpath_rate >= 0.f && o.light_subpath_rate == kLightSubpathsAuto && !o.debug_unit_mis_weights)
    logging::info(
        "light subpaths: 1 per camera sample (--light-subpaths auto): the render is too small for its pilot "
        "to pay, which needs 16 times the pilot's samples or a time budget");
  if (!s.light_choice.empty() && s.light_subpath_rate > 0.f)
    logging::info("light subpaths choose their light: %s, the pilot's choice", s.light_choice.c_str());
  if (s.timed && logging::enabled(logging::Level::Info)) print_stage_summary(s);
  logging::verbose("memory: peak %.1f MB resident; wave pools %.1f MB", double(peak_rss_bytes()) * 1e-6,
               double(s.wave_pool_bytes) * 1e-6);
  if (s.texture_failed_lookups > 0)
    logging::warning("warning: %lld texture lookups failed (a texture file could not be read during the render); they "
                 "read as 0",
                 (long long)s.texture_failed_lookups);
}

// Every file the render will write, checked before the render starts (the
// ones known before loading, before loading: a scene can take minutes).
void check_outputs(const RenderArgs& a, const std::string& out, bool loaded) {
  if (loaded && !a.output.empty()) return;  // checked before loading
  if (!loaded && a.output.empty()) return;  // the scene names it
  if (a.part.empty()) check_image_path(out);
  else if (out == "-") throw cli::UsageError("--part writes a part file, not to standard output: name it with -o");
  else check_writable(out, "the part file");
}

// At most one output goes to standard output, and nothing else is written
// there.
void check_standard_output(const RenderArgs& a, const std::string& out) {
  int n = int(out == "-") + int(a.stats == "-") + int(a.trace == "-") + int(a.dump_rays == "-");
  if (n > 1)
    throw cli::UsageError("only one output can go to standard output (\"-\"): the image, --stats, --trace or "
                                "--dump-rays");
  if (out == "-" && !a.partial_images.empty())
    throw cli::UsageError("--write-partial-images needs an image file (-o NAME), not standard output");
}

RenderOptions options_for(const RenderArgs& a, const Scene& scene, const std::string& out, const Ranks& ranks) {
  RenderOptions o = resolve_render_options(scene, a.req);
  o.strategies = !a.strategies.empty();
  o.collect_stats = !a.stats.empty();
  o.dump_rays = a.dump_rays == "-" ? "/dev/stdout" : a.dump_rays;
  if (!a.part.empty()) {
    // The part file instead of an image: `lantern merge` makes the image.
    long long k = 1, n = 1;
    cli::parse_part(a.part, k, n);
    o.share_index = uint32_t(k - 1);
    o.share_count = uint32_t(n);
    o.film_path = out;
  }
  // Across ranks always: a job ended from outside (a batch system's time
  // limit, a rank lost, Ctrl-C) leaves every surviving rank's work in its
  // piece of the checkpoint, for --resume; a job that completes leaves none.
  // The scene's fingerprint goes into checkpoints and parts alike, so that
  // neither is resumed or merged with another scene's.
  o.checkpoint_key = scene_key(a.scene, scene_info(scene));
  if (a.checkpoint > 0 || a.resume || a.keep_checkpoint || ranks.count > 1) {
    o.checkpoint_path = a.checkpoint_file.empty() ? out + ".ckpt" : a.checkpoint_file;
    o.checkpoint_seconds = a.checkpoint;
    o.resume = a.resume;
    o.keep_checkpoint = a.keep_checkpoint;
  }
  if (o.checkpoint_path == "-.ckpt") o.checkpoint_path = "stdout.ckpt";
  return o;
}

void log_settings(const Scene& scene, const RenderOptions& o) {
  const ImageRegion region = image_region(scene, o);
  std::string budget = o.time_limit_seconds > 0 ? std::to_string(o.time_limit_seconds) + " s" : std::to_string(o.spp) + " spp";
  logging::verbose("render: %s, %s, maxdepth %d, seed %llu, sampler %s, light sampler %s, %s, %dx%d%s, wave size %d, %d "
               "threads",
               name(o.integrator), budget.c_str(), o.maxdepth, (unsigned long long)o.seed, name(o.sampler.type),
               name(o.light_sampler), o.spectral ? "spectral" : "RGB", region.width, region.height,
               region.cropped() ? (" (of " + std::to_string(region.full_width) + "x" + std::to_string(region.full_height) +
                                   " from " + std::to_string(region.x0) + "," + std::to_string(region.y0) + ")")
                                      .c_str()
                                : "",
               o.wave_size, o.threads > 0 ? o.threads : int(std::max(1L, sysconf(_SC_NPROCESSORS_ONLN))));
}

}  // namespace

void add_render_command_options(CLI::App& render, RenderArgs& a) {
  render.add_option("scene", a.scene, "Scene file (pbrt-v4 format)")->required();
  render.add_option("-o,--output", a.output,
                    "Output image (.exr linear float, .png sRGB; -: OpenEXR on standard output); default: the scene's "
                    "Film filename");
  cli::add_render_request_options(render, a.req);
  render.add_option("--progress-interval", a.progress_interval,
                    "When stderr is not a terminal (a batch job's log): a progress line every this many seconds "
                    "(0: none)")
      ->check(cli::number_in(0.0, 1e9, true, "a number of seconds, 0 or more"));
  // A flag with an optional value after "=" (never the next word, which may
  // be the scene).
  render.add_flag("--write-partial-images{10}", a.partial_images,
                  "Write the image so far over the output at the end of a pass, at most every 10 seconds, or every "
                  "SECONDS with --write-partial-images=SECONDS; pbrt-v4's flag")
      ->check(cli::number_in(0.0, 1e9, false, "a positive number of seconds"));
  render.add_option("--log-level", a.log_level,
                    "What to say on stderr: error, warning, info (the progress line and summary; the default) or "
                    "verbose (each loading stage, the settings, each pass, memory)")
      ->check(CLI::IsMember({"error", "warning", "info", "verbose", "fatal"}));
  render.add_option("--log-file", a.log_file, "Append messages to FILE instead of stderr (errors go to both)");
  render.add_option("--stats", a.stats,
                    "Write measurements as JSON: time per stage, rays by kind, subpath lengths, memory (-: stdout)");
  render.add_option("--dump-rays", a.dump_rays,
                    "Write every ray batch given to Embree to FILE (32 bytes a ray; for perf/'s ray benchmark)");
  render.add_option("--strategies", a.strategies,
                    "bdpt, vcm, bpm, ppm: write DIR/s<s>_t<t>_{weighted,unweighted}.exr, one pair per strategy "
                    "(merge_s<s>_t<t> for merges)");
  render.add_option("--checkpoint", a.checkpoint,
                    "Write the render's state every SECONDS (and on Ctrl-C/SIGTERM) to OUTPUT.ckpt")
      ->check(cli::positive_seconds());
  render.add_option("--checkpoint-file", a.checkpoint_file, "Checkpoint file (default: the output's name + .ckpt)");
  render.add_flag("--keep-checkpoint", a.keep_checkpoint,
                  "Keep the checkpoint when the render completes, so that --resume with a larger --spp extends it");
  render.add_flag("--resume", a.resume,
                  "Continue from the checkpoint; the result equals an uninterrupted render with the same settings");
  render.add_option("--texture-cache", a.texture_cache_mb,
                    "Memory for image texture tiles, in MB (default: 1024); the image does not depend on it")
      ->check(cli::number_in(1.0, 1048576.0, true, "a number of megabytes from 1 to 1048576"));
  render.add_option("--memory-layout", a.memory_layout,
                    "fast (Embree's instances and BVH), compact (instances at 56 bytes and a box, Embree's compact "
                    "BVH: less memory, 8-16% slower on small scenes) or auto (compact instances from 100,000, "
                    "compact BVH from 10M primitives; the default); the image is the same")
      ->check(CLI::IsMember({"auto", "fast", "compact"}));
  render.add_flag("--lenient", a.lenient,
                  "A scene parameter neither pbrt-v4 nor pbrt-v3 reads (a typo) is a warning, not an error");
  render.add_option("--texture-dir", a.texture_dir,
                    "Where images are prepared as tiled, MIP-mapped textures (default: ~/.cache/lantern/textures)");
  render.add_option("--trace", a.trace,
                    "Write a timeline of the render to FILE.json (Chrome trace events: open it in Perfetto or "
                    "chrome://tracing; docs/profiling.md)");
  render.add_option("--trace-waves", a.trace_waves,
                    "With --trace: keep the first N waves in full, later ones as counters only (default 1000; 0: all)")
      ->check(cli::integer_in(0, 9223372036854775807LL, "an integer of 0 or more"));
  render.add_option("--part", a.part,
                    "Render part K of N of the render's work into a part file (-o; default: the output's name + "
                    ".partKofN); `lantern merge` adds the parts into the image")
      ->check(cli::part_of());
  render.add_option("--display-server", a.display_server,
                    "Stream the image as it refines to a viewer speaking tev's protocol at HOST:PORT (tev "
                    "listens on 127.0.0.1:14158)");
  render.add_flag("-q,--quiet", a.quiet, "No progress line or summary (--log-level warning)");
}

int run_render(const RenderArgs& a, const Provenance& provenance, const Ranks& ranks) {
  // One log file for the job: rank 0's (the others keep stderr).
  logging::configure(a.quiet && a.log_level == "info" ? logging::Level::Warning : logging::parse_level(a.log_level),
                     ranks.rank == 0 ? a.log_file : std::string());
  // From the start: a signal during loading stops the render before its
  // first wave, and the (empty) image is still written, with exit 130.
  // Installed only later, such a signal killed the process with no image.
  std::signal(SIGINT, on_signal);
  std::signal(SIGTERM, on_signal);
  if (ranks.count > 1) {
    auto refuse = [](const char* what) {
      throw std::runtime_error(std::string(what) + " cannot be used with several MPI ranks yet");
    };
    if (!a.part.empty()) refuse("--part");
    if (!a.strategies.empty()) refuse("--strategies");
    if (!a.dump_rays.empty()) refuse("--dump-rays");
    if (!a.partial_images.empty()) refuse("--write-partial-images");
  }
  if (!a.part.empty() && !a.partial_images.empty())
    throw cli::UsageError("--write-partial-images writes images; a part (--part) writes a part file, merged later");
  const bool writes = ranks.rank == 0;  // only rank 0 writes the image and reports
  if (writes) {
    check_standard_output(a, a.output);
    check_outputs(a, a.output, false);
    if (!a.stats.empty()) check_writable(a.stats, "the statistics");
    if (!a.trace.empty()) check_writable(a.trace, "the trace");
  }
  std::unique_ptr<Timeline> timeline;
  if (!a.trace.empty()) timeline = std::make_unique<Timeline>(a.trace_waves);
  const Loaded loaded = load(a, timeline.get(), writes);
  const Scene& scene = *loaded.scene;
  const SceneSettings& ss = scene_settings(scene);

  std::string out = a.output.empty() ? ss.output : a.output;
  long long part_k = 1, part_n = 1;
  if (!a.part.empty() && a.output.empty()) {
    cli::parse_part(a.part, part_k, part_n);
    out = ss.output + ".part" + std::to_string(part_k) + "of" + std::to_string(part_n);
  }
  RenderOptions o = options_for(a, scene, out, ranks);
  if ((o.gbuffer || o.spectral_buckets > 0) && out != "-" && a.part.empty()) {
    std::string ext = std::filesystem::path(out).extension().string();
    for (char& c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
    if (ext != ".exr")
      throw cli::UsageError(std::string("Film \"") + (o.gbuffer ? "gbuffer" : "spectral") +
                            "\" writes its channels to OpenEXR only, as pbrt-v4's does: \"" + out +
                            "\" is not .exr (name the output with -o NAME.exr)");
  }
  if (ss.dispersive && !o.spectral && writes)
    logging::warning("warning: the scene has a material whose index of refraction varies with wavelength; it disperses "
                 "light only with --spectral (in RGB its index is the one at 587.6 nm)");
  if (const std::string note = reframing_note(scene, o); !note.empty() && writes) logging::info("note: %s", note.c_str());
  RenderHooks hooks;
  hooks.cancel = &g_cancel;
  hooks.timeline = timeline.get();
  // The time to the first image (loading, then the first pass over every
  // pixel): what a production scene makes its users wait for.
  const auto render_begin = std::chrono::steady_clock::now();
  double first_pass_seconds = -1.0;
  hooks.pass_done = [&first_pass_seconds, render_begin](uint32_t) {
    if (first_pass_seconds < 0.0)
      first_pass_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - render_begin).count();
  };
  ImageRegion region;  // on every rank: each fails alike on a region outside the image
  try {
    region = image_region(scene, o);
  } catch (const std::invalid_argument& e) {
    // A region of the command line outside this scene's image: its error.
    if (!a.req.crop_window.empty() || !a.req.pixel_bounds.empty() || !a.req.pixel.empty()) throw cli::UsageError(e.what());
    throw;
  }
  if (writes) {
    hooks.progress = progress_line(a.progress_interval, double(region.width) * double(region.height));
    check_standard_output(a, out);
    check_outputs(a, out, true);
    if (!o.checkpoint_path.empty()) check_writable(o.checkpoint_path, "the checkpoint");
    log_settings(scene, o);
  }
  if (!a.strategies.empty()) std::filesystem::create_directories(a.strategies);

  Watchers watchers;
  if (writes) {
    watchers.log_passes = true;
    watchers.display_server = a.display_server;
    watchers.display_name = out;
    if (!a.partial_images.empty()) {
      watchers.partial_path = out;
      watchers.partial_seconds = std::stod(a.partial_images);
      watchers.partial_metadata = [&](const RenderResult& partial) {
        ImageMetadata md = render_metadata(scene, a.scene, o, partial, provenance);
        md.emplace_back("lantern:partial", "true");
        return md;
      };
    }
  }
  RenderResult r;
  nlohmann::json rank_stats;  // under mpirun: per-rank figures for --stats
  {
#ifdef LANTERN_HAVE_MPI
    std::optional<MpiRender> mpi;
    if (ranks.mpi && ranks.count > 1) {
      mpi.emplace(*ranks.mpi, o, hooks);
      if (!writes) {
        hooks.progress = [&mpi](const RenderProgress& p) { mpi->note_local_samples(p.samples_done); };
      } else if (hooks.progress) {
        // One line for the job: the other ranks' samples added to ours.
        hooks.progress = [&mpi, show = hooks.progress, timed = o.time_limit_seconds > 0](RenderProgress p) {
          p.samples_done += mpi->remote_samples();
          if (!timed) p.fraction = std::min(1.0, double(p.samples_done) / double(std::max<uint64_t>(p.samples_total, 1)));
          show(p);
        };
      }
    }
#endif
    {
      TraceSpan span(timeline ? &timeline->main() : nullptr, "render", TraceCategory::Render);
      r = render_watched(scene, o, hooks, watchers);
    }
    logging::end_progress();
#ifdef LANTERN_HAVE_MPI
    if (mpi) {
      // The job's rays in the summary (samples are the reduced film's).
      const auto reports = mpi->gather(r.stats);
      if (!reports.empty()) {
        uint64_t rays[4] = {0, 0, 0, 0};
        for (const auto& rep : reports)
          for (int k = 0; k < 4; ++k) rays[k] += uint64_t(rep.rays[k]);
        r.stats.camera_rays = rays[0];
        r.stats.extension_rays = rays[1];
        r.stats.light_rays = rays[2];
        r.stats.shadow_rays = rays[3];
        rank_stats = rank_report_json(reports);
      }
    }
#endif
  }
  if (!writes) return r.interrupted ? 130 : 0;  // rank 0 has the image
  auto write_stats = [&] {
    RunInfo run{a.scene,        name(o.integrator), out, name(o.ray_backend), r.image.width, r.image.height,
                o.wave_size,    loaded.seconds,     scene_info(scene), ss.sampler, o.sampler, name(ss.light_sampler),
                loaded.phases};
    nlohmann::json j = stats_json(run, r.stats);
    if (first_pass_seconds >= 0.0) j["seconds"]["first_image"] = loaded.seconds + first_pass_seconds;
    j["colour"] = o.spectral ? "spectral" : "rgb";
    j["settings"] = render_settings_json(o);
    j["provenance"] = provenance_json(provenance);
    if (!rank_stats.is_null()) j["mpi"] = rank_stats;
    write_text_atomically(a.stats, j.dump(2) + "\n");
  };
  if (!a.part.empty()) {
    if (!a.stats.empty()) write_stats();
    return finish_part(a, o, r, timeline.get());
  }

  const ImageMetadata md = render_metadata(scene, a.scene, o, r, provenance);
  ImageWrite written;
  {
    TraceSpan span(timeline ? &timeline->main() : nullptr, "write image", TraceCategory::Output);
    written = write_image_or_rescue(out, r.image, md, o.checkpoint_path);
    if (!a.strategies.empty()) write_strategy_images(a.strategies, r.strategies, md);
  }
  if (timeline) write_text_atomically(a.trace, timeline->json());  // interrupted renders too
  if (!written.written) {
    logging::error("error: %s", written.error.c_str());
    if (!written.rescue.empty()) logging::error("the rendered image is saved instead in %s", written.rescue.c_str());
    else logging::error("error: no rescue copy could be written either; the image is lost");
    return 1;
  }
  report(out == "-" ? std::string("(standard output)") : out, o, r, loaded.seconds);
  if (!a.stats.empty()) write_stats();
  if (r.interrupted) {
    logging::error("interrupted: wrote the %llu samples rendered so far to %s", (unsigned long long)r.stats.samples,
               out.c_str());
    if (!o.checkpoint_path.empty()) logging::error("checkpoint: %s (continue with --resume)", o.checkpoint_path.c_str());
    return 130;
  }
  return 0;
}

}  // namespace lantern
