// The lantern command line.
#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>
#include <unistd.h>

#include <atomic>
#include <cmath>
#include <csignal>
#include <filesystem>
#include <fstream>
#include <cstdio>
#include <iostream>
#include <optional>
#include <sstream>

#include "app/cli_checks.h"
#include "app/command_line.h"
#include "app/display_server.h"
#include "app/merge_command.h"
#include "app/outputs.h"
#include "app/provenance.h"
#include "app/render_request.h"
#include "app/viewer.h"
#include "app/stats_report.h"
#include "integrator/render_settings.h"
#include "trace/timeline.h"
#include "film/checkpoint.h"
#include "film/image_metrics.h"
#include "imageio/replace_file.h"
#include "lantern/render.h"
#include "lantern/scene.h"
#ifdef LANTERN_HAVE_MPI
#include "distributed/mpi_render.h"
#endif

namespace {

std::atomic<bool> g_cancel{false};

lantern::Provenance g_provenance;  // of this run: the machine, the date, the command

// This process's place among MPI ranks (rank 0 of 1 without mpirun).
int g_rank = 0, g_ranks = 1;
#ifdef LANTERN_HAVE_MPI
lantern::MpiSession* g_mpi = nullptr;
#endif

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

struct RenderArgs {
  lantern::RenderRequest req;  // what the render options ask of the scene
  std::string scene, output, strategies, stats, dump_rays, checkpoint_file;
  std::string texture_dir, trace, part, display_server;
  uint64_t trace_waves = 1000;
  double checkpoint = 0.0, texture_cache_mb = 1024.0, progress_interval = 10.0;
  bool resume = false, keep_checkpoint = false;
  bool quiet = false;
};

void write_strategy_images(const std::string& dir, const std::vector<lantern::StrategyImage>& images,
                           const lantern::ImageMetadata& md) {
  std::filesystem::create_directories(dir);
  for (const lantern::StrategyImage& im : images) {
    std::string base = dir + (im.merge ? "/merge_s" : "/s") + std::to_string(im.s) + "_t" + std::to_string(im.t);
    lantern::write_image(base + "_weighted.exr", im.weighted, md);
    lantern::write_image(base + "_unweighted.exr", im.unweighted, md);
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
  std::string tmp = lantern::temporary_output(path, "");
  {
    std::ofstream f(tmp, std::ios::binary);
    f << text;
    if (!f.flush()) throw std::runtime_error("cannot write " + tmp);
  }
  lantern::place_output(tmp, path);
}

// Loading as spans on the timeline's main track: the whole load, and each
// stage the loader reports (parsing, reading PLY meshes, building the BVH).
class LoadTrace {
 public:
  explicit LoadTrace(lantern::Timeline* t) : timeline_(t), begin_(lantern::TraceClock::now()), stage_begin_(begin_) {}
  void stage(const std::string& name) {
    if (!timeline_) return;
    close_stage();
    stage_ = timeline_->intern(name);
  }
  void done() {
    if (!timeline_) return;
    close_stage();
    timeline_->main().span("load", lantern::TraceCategory::Load, begin_, lantern::TraceClock::now());
  }

 private:
  void close_stage() {
    const auto now = lantern::TraceClock::now();
    timeline_->main().span(stage_, lantern::TraceCategory::Load, stage_begin_, now);
    stage_begin_ = now;
  }
  lantern::Timeline* timeline_;
  lantern::TraceClock::time_point begin_, stage_begin_;
  const char* stage_ = "parse";
};

// A part's render has written its file (render() does, finished or not).
int finish_part(const RenderArgs& a, const lantern::RenderOptions& o, const lantern::RenderResult& r,
                lantern::Timeline* timeline) {
  if (timeline) write_text_atomically(a.trace, timeline->json());
  if (!a.quiet)
    std::fprintf(stderr, "%s: part %s, %llu samples, %.2f s render\n", o.film_path.c_str(), a.part.c_str(),
                 (unsigned long long)r.stats.samples, r.stats.seconds);
  if (r.interrupted) {
    std::fprintf(stderr, "interrupted: %s holds the part so far (merge it with --preview, or finish it with "
                         "--checkpoint and --resume)\n", o.film_path.c_str());
    return 130;
  }
  return 0;
}

#ifdef LANTERN_HAVE_MPI
nlohmann::json rank_report_json(const std::vector<lantern::MpiRender::RankReport>& reports) {
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

// The render, streamed to a display server as it refines when one is
// named (app/display_server.h). A server that cannot be reached is a
// warning: the render does not depend on it.
lantern::RenderResult render_watched(const lantern::Scene& scene, const lantern::RenderOptions& o,
                                     lantern::RenderHooks hooks, const std::string& display_server,
                                     const std::string& image_name) {
  if (display_server.empty()) return lantern::render(scene, o, hooks);
  std::unique_ptr<lantern::DisplayServer> display;
  hooks.pass_done = [&display, earlier = hooks.pass_done](uint32_t spp) {
    if (earlier) earlier(spp);
    if (display) display->pass_done();
  };
  lantern::RenderSession session(scene, o, hooks);
  try {
    display = std::make_unique<lantern::DisplayServer>(display_server, image_name, session.width(), session.height());
    display->watch(session);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "warning: %s; rendering without it\n", e.what());
  }
  lantern::RenderResult r;
  try {
    r = session.run();
  } catch (...) {
    display.reset();  // its thread reads the session: stopped before the session goes
    throw;
  }
  if (display) display->stop(r.image);
  return r;
}

int run_render(const RenderArgs& a) {
  using namespace lantern;
  // From the start: a signal during loading stops the render before its
  // first wave, and the (empty) image is still written, with exit 130.
  // Installed only later, such a signal killed the process with no image.
  std::signal(SIGINT, on_signal);
  std::signal(SIGTERM, on_signal);
  LoadOptions lo;
  lo.texture_cache_mb = a.texture_cache_mb;
  lo.texture_directory = a.texture_dir;
  const bool show_progress = !a.quiet && g_rank == 0 && isatty(STDERR_FILENO);
  long long part_k = 1, part_n = 1;
  if (!a.part.empty()) cli::parse_part(a.part, part_k, part_n);
  if (g_ranks > 1) {
    auto refuse = [](const char* what) {
      throw std::runtime_error(std::string(what) + " cannot be used with several MPI ranks yet");
    };
    if (!a.part.empty()) refuse("--part");
    if (!a.strategies.empty()) refuse("--strategies");
    if (!a.dump_rays.empty()) refuse("--dump-rays");
  }
  const bool writes = g_rank == 0;  // only rank 0 writes the image and reports
  // Outputs known before loading are checked before loading: a scene can
  // take minutes to load.
  if (!a.output.empty() && writes) {
    if (a.part.empty()) check_image_path(a.output);
    else check_writable(a.output, "the part file");
  }
  if (!a.stats.empty() && writes) check_writable(a.stats, "the statistics");
  if (!a.trace.empty() && writes) check_writable(a.trace, "the trace");
  std::unique_ptr<Timeline> timeline;
  if (!a.trace.empty()) timeline = std::make_unique<Timeline>(a.trace_waves);
  LoadTrace load_trace(timeline.get());
  auto t0 = std::chrono::steady_clock::now();
  // A progress line while loading: the stage and the time so far.
  bool progress_shown = false;
  lo.warn = [&](const std::string& w) {
    if (progress_shown) std::fprintf(stderr, "\n");
    progress_shown = false;
    std::cerr << w << "\n";
  };
  if (show_progress || timeline)
    lo.progress = [&](const std::string& stage) {
      load_trace.stage(stage);
      if (!show_progress) return;
      double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      std::fprintf(stderr, "\r\033[K[load %6.1f s] %s", s, stage.c_str());
      std::fflush(stderr);
      progress_shown = true;
    };
  std::shared_ptr<Scene> scene = load_scene(a.scene, lo);
  load_trace.done();
  double load_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  if (progress_shown) std::fprintf(stderr, "\r\033[K[load %6.1f s] done\n", load_s);
  const SceneSettings& ss = scene_settings(*scene);

  RenderOptions o = resolve_render_options(*scene, a.req);
  if (ss.dispersive && !o.spectral)
    std::fprintf(stderr, "warning: the scene has a material whose index of refraction varies with wavelength; it "
                         "disperses light only with --spectral (in RGB its index is the one at 587.6 nm)\n");
  o.strategies = !a.strategies.empty();
  o.collect_stats = !a.stats.empty();
  o.dump_rays = a.dump_rays;
  RenderHooks hooks;
  hooks.cancel = &g_cancel;
  std::string out = a.output.empty() ? ss.output : a.output;
  if (!a.part.empty()) {
    // The part file instead of an image: `lantern merge` makes the image.
    if (a.output.empty()) out = ss.output + ".part" + std::to_string(part_k) + "of" + std::to_string(part_n);
    o.share_index = uint32_t(part_k - 1);
    o.share_count = uint32_t(part_n);
    o.film_path = out;
  }
  // Across ranks always: a job ended from outside (a batch system's time
  // limit, a rank lost, Ctrl-C) leaves every surviving rank's work in its
  // piece of the checkpoint, for --resume; a job that completes leaves none.
  // The scene's fingerprint goes into checkpoints and parts alike, so that
  // neither is resumed or merged with another scene's.
  o.checkpoint_key = scene_key(a.scene, scene_info(*scene));
  if (a.checkpoint > 0 || a.resume || a.keep_checkpoint || g_ranks > 1) {
    o.checkpoint_path = a.checkpoint_file.empty() ? out + ".ckpt" : a.checkpoint_file;
    o.checkpoint_seconds = a.checkpoint;
    o.resume = a.resume;
    o.keep_checkpoint = a.keep_checkpoint;
  }
  // On a terminal, a line rewritten in place. Otherwise (a batch job's log,
  // mpirun's pipes) a whole line every --progress-interval seconds.
  const bool tty = isatty(STDERR_FILENO);
  if (!a.quiet && writes && (tty || a.progress_interval > 0)) {
    const double pixels = double(o.width > 0 ? o.width : ss.width) * double(o.height > 0 ? o.height : ss.height);
    hooks.progress = [tty, interval = a.progress_interval, pixels, last = -1e9](const RenderProgress& p) mutable {
      if (!tty && p.elapsed_seconds - last < interval && p.fraction < 1.0) return;
      last = p.elapsed_seconds;
      double eta = p.fraction > 0 ? p.elapsed_seconds * (1.0 - p.fraction) / p.fraction : 0.0;
      double rate = p.elapsed_seconds > 0 ? double(p.samples_done) / p.elapsed_seconds : 0.0;
      std::fprintf(stderr, "%s[%5.1f%%] %s elapsed, ETA %s, %.1f spp, %.2f Msamples/s%s", tty ? "\r" : "",
                   100.0 * p.fraction, hms(p.elapsed_seconds).c_str(), hms(eta).c_str(),
                   double(p.samples_done) / std::max(pixels, 1.0), rate * 1e-6, tty ? "   " : "\n");
      std::fflush(stderr);
    };
  }
  // Every file the render will write, before it starts.
  if (a.output.empty() && writes) {
    if (a.part.empty()) check_image_path(out);
    else check_writable(out, "the part file");
  }
  if (!o.checkpoint_path.empty() && writes) check_writable(o.checkpoint_path, "the checkpoint");
  if (!a.strategies.empty()) std::filesystem::create_directories(a.strategies);
  hooks.timeline = timeline.get();
  RenderResult r;
  nlohmann::json rank_stats;  // under mpirun: per-rank figures for --stats
  {
#ifdef LANTERN_HAVE_MPI
    std::optional<MpiRender> ranks;
    if (g_mpi && g_ranks > 1) {
      ranks.emplace(*g_mpi, o, hooks);
      if (g_rank != 0) {
        hooks.progress = [&ranks](const RenderProgress& p) { ranks->note_local_samples(p.samples_done); };
      } else if (hooks.progress) {
        // One line for the job: the other ranks' samples added to ours.
        hooks.progress = [&ranks, show = hooks.progress, timed = o.time_limit_seconds > 0](RenderProgress p) {
          p.samples_done += ranks->remote_samples();
          if (!timed) p.fraction = std::min(1.0, double(p.samples_done) / double(std::max<uint64_t>(p.samples_total, 1)));
          show(p);
        };
      }
    }
#endif
    {
      TraceSpan span(timeline ? &timeline->main() : nullptr, "render", TraceCategory::Render);
      r = render_watched(*scene, o, hooks, writes ? a.display_server : std::string(), out);
    }
#ifdef LANTERN_HAVE_MPI
    if (ranks) {
      // The job's rays in the summary (samples are the reduced film's).
      const auto reports = ranks->gather(r.stats);
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
  if (hooks.progress && isatty(STDERR_FILENO)) std::fprintf(stderr, "\n");
  if (!writes) return r.interrupted ? 130 : 0;  // rank 0 has the image
  auto write_stats = [&] {
    RunInfo run{a.scene, name(o.integrator), out, name(o.ray_backend), r.image.width, r.image.height, o.wave_size, load_s,
                scene_info(*scene), scene_settings(*scene).sampler, o.sampler, name(scene_settings(*scene).light_sampler)};
    nlohmann::json j = stats_json(run, r.stats);
    j["colour"] = o.spectral ? "spectral" : "rgb";
    j["settings"] = render_settings_json(o);
    j["provenance"] = provenance_json(g_provenance);
    if (!rank_stats.is_null()) j["mpi"] = rank_stats;
    write_text_atomically(a.stats, j.dump(2) + "\n");
  };
  if (!a.part.empty()) {
    if (!a.stats.empty()) write_stats();
    return finish_part(a, o, r, timeline.get());
  }

  const ImageMetadata md = render_metadata(*scene, a.scene, o, r, g_provenance);
  ImageWrite written;
  {
    TraceSpan span(timeline ? &timeline->main() : nullptr, "write image", TraceCategory::Output);
    written = write_image_or_rescue(out, r.image, md, o.checkpoint_path);
    if (!a.strategies.empty()) write_strategy_images(a.strategies, r.strategies, md);
  }
  if (timeline) write_text_atomically(a.trace, timeline->json());  // interrupted renders too
  if (!written.written) {
    std::fprintf(stderr, "error: %s\n", written.error.c_str());
    if (!written.rescue.empty()) {
      std::fprintf(stderr, "the rendered image is saved instead in %s\n", written.rescue.c_str());
    } else {
      std::fprintf(stderr, "error: no rescue copy could be written either; the image is lost\n");
    }
    return 1;
  }
  if (!a.quiet) {
    const RenderStats& s = r.stats;
    double rays = double(s.camera_rays + s.extension_rays + s.light_rays + s.shadow_rays);
    std::fprintf(stderr,
                 "%s: %dx%d, %u spp (min), %.2f s render, %.2f s load; %.3f Msamples/s, %.2f Mrays/s "
                 "(camera %.1fM, eye extension %.1fM, light extension %.1fM, shadow/connection %.1fM); "
                 "non-finite samples discarded: %llu\n",
                 out.c_str(), r.image.width, r.image.height, s.min_spp, s.seconds, load_s,
                 double(s.samples - r.resumed_samples) / s.seconds * 1e-6, rays / s.seconds * 1e-6, double(s.camera_rays) * 1e-6,
                 double(s.extension_rays) * 1e-6, double(s.light_rays) * 1e-6, double(s.shadow_rays) * 1e-6,
                 (unsigned long long)s.nonfinite_samples);
    if (s.estimated_relmse >= 0)
      std::fprintf(stderr, "adaptive sampling: %u to %u spp, %.1f on average; estimated relative MSE %.3g (target %.3g)\n",
                   s.min_spp, s.max_spp, double(s.samples) / (double(r.image.width) * double(r.image.height)),
                   s.estimated_relmse, o.target_error);
    if (s.timed) print_stage_summary(s);
  }
  if (r.stats.texture_failed_lookups > 0)
    std::fprintf(stderr, "warning: %lld texture lookups failed (a texture file could not be read during the render); they read as 0\n",
                 (long long)r.stats.texture_failed_lookups);
  if (!a.stats.empty()) write_stats();
  if (r.interrupted) {
    std::fprintf(stderr, "interrupted: wrote the %llu samples rendered so far to %s\n",
                 (unsigned long long)r.stats.samples, out.c_str());
    if (!o.checkpoint_path.empty())
      std::fprintf(stderr, "checkpoint: %s (continue with --resume)\n", o.checkpoint_path.c_str());
    return 130;
  }
  return 0;
}

struct CompareArgs {
  std::string a, ref, error_image;
  double error_scale = 1.0;
  bool json = false;
};

// Prints the metrics as "name value" lines, easy to read and to parse, or
// as one JSON object (--json; an infinite PSNR, of identical images, is null).
int run_compare(const CompareArgs& c) {
  lantern::Image a = lantern::read_image(c.a), ref = lantern::read_image(c.ref);
  const lantern::ImageComparison m = lantern::compare_images(a, ref);
  if (c.json) {
    nlohmann::json j = {{"image", c.a}, {"reference", c.ref}, {"width", a.width}, {"height", a.height}};
    j.update(lantern::comparison_json(m));
    std::printf("%s\n", j.dump(2).c_str());
  } else {
    // (The first seven lines as they have always been; the others after.)
    std::printf("mse %.9g\nrelmse %.9g\nmae %.9g\n", m.mse, m.relmse, m.mae);
    std::printf("mean %.9g %.9g %.9g\nmean_ref %.9g %.9g %.9g\nratio %.9g %.9g %.9g\nnonfinite_pixels %zu\n",
                m.mean_a[0], m.mean_a[1], m.mean_a[2], m.mean_ref[0], m.mean_ref[1], m.mean_ref[2], m.ratio[0],
                m.ratio[1], m.ratio[2], m.nonfinite);
    std::printf("psnr %.9g\nrelmse_robust %.9g\nrobust_excluded_pixels %zu\n", m.psnr, m.relmse_robust,
                m.robust_excluded);
    std::printf("pbrt_mse %.9g %.9g %.9g\npbrt_mrse %.9g %.9g %.9g\n", m.pbrt_mse[0], m.pbrt_mse[1], m.pbrt_mse[2],
                m.pbrt_mrse[0], m.pbrt_mrse[1], m.pbrt_mrse[2]);
  }
  if (!c.error_image.empty())
    lantern::write_image(c.error_image, lantern::relative_error_image(a, ref, c.error_scale, true),
                         {{"lantern:error_map", "relative squared error per pixel, blue 0 to red " +
                                                    std::to_string(c.error_scale) +
                                                    " and above; the bar below: the scale, 0 to " +
                                                    std::to_string(c.error_scale)}});
  return 0;
}

// "name value" lines: the size and the render settings an image was made
// with; for a checkpoint or a part file, the settings of the render it
// belongs to (its fingerprint), the units it holds and its samples.
int run_info(const std::string& path) {
  std::string fingerprint;
  try {
    fingerprint = lantern::read_checkpoint_fingerprint(path);
  } catch (const lantern::InputError&) {  // not one: an image
    lantern::Image img = lantern::read_image(path);
    std::printf("resolution %d %d\n", img.width, img.height);
    for (const auto& [k, v] : lantern::read_image_metadata(path)) std::printf("%s %s\n", k.c_str(), v.c_str());
    return 0;
  }
  lantern::Film film(0, 0, lantern::PixelFilter{});
  const lantern::CheckpointInfo ci = lantern::read_film_file(path, film);
  std::istringstream lines(fingerprint);
  for (std::string line; std::getline(lines, line);)
    if (const size_t eq = line.find('='); eq != std::string::npos)
      std::printf("%s %s\n", line.substr(0, eq).c_str(), line.substr(eq + 1).c_str());
  std::printf("part %u/%u\nunits_done %llu\nunits_total %llu\nsamples %llu\nrender_seconds %.3f\n",
              ci.share.index + 1, ci.share.count, (unsigned long long)ci.done.size(),
              (unsigned long long)(uint64_t(ci.passes) * ci.waves), (unsigned long long)film.total_samples(),
              ci.elapsed_seconds);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
#ifdef LANTERN_HAVE_MPI
  // Under mpirun: MPI for the whole run. A rank that fails ends them all
  // (MPI_Abort) rather than leaving the others waiting for it.
  std::unique_ptr<lantern::MpiSession> mpi;
  if (lantern::MpiSession::launched()) {
    mpi = std::make_unique<lantern::MpiSession>(argc, argv);
    g_mpi = mpi.get();
    g_rank = mpi->rank();
    g_ranks = mpi->size();
  }
  auto fail = [&](int code) {
    if (g_ranks > 1) {
      std::cerr << "rank " << g_rank << " of " << g_ranks << " failed; ending all ranks\n";
      mpi->abort_all(code);
    }
    return code;
  };
#else
  auto fail = [](int code) { return code; };
#endif
  g_provenance = lantern::provenance(argc, argv);
  CLI::App app{"Lantern: physically based rendering with bidirectional path tracing"};
  app.require_subcommand(1);
  RenderArgs a;
  CLI::App* render = app.add_subcommand("render", "Render a pbrt-v4 scene to an image");
  render->add_option("scene", a.scene, "Scene file (pbrt-v4 format)")->required();
  render->add_option("-o,--output", a.output, "Output image (.exr linear float, .png sRGB); default: the scene's Film filename");
  lantern::cli::add_render_request_options(*render, a.req);
  render->add_option("--progress-interval", a.progress_interval,
                     "When stderr is not a terminal (a batch job's log): a progress line every this many seconds "
                     "(0: none)")
      ->check(lantern::cli::number_in(0.0, 1e9, true, "a number of seconds, 0 or more"));
  render->add_option("--stats", a.stats,
                     "Write measurements as JSON: time per stage, rays by kind, subpath lengths, memory");
  render->add_option("--dump-rays", a.dump_rays,
                     "Write every ray batch given to Embree to FILE (32 bytes a ray; for perf/'s ray benchmark)");
  render->add_option("--strategies", a.strategies,
                     "bdpt, vcm, bpm, ppm: write DIR/s<s>_t<t>_{weighted,unweighted}.exr, one pair per strategy (merge_s<s>_t<t> for merges)");
  render->add_option("--checkpoint", a.checkpoint,
                     "Write the render's state every SECONDS (and on Ctrl-C/SIGTERM) to OUTPUT.ckpt")
      ->check(lantern::cli::positive_seconds());
  render->add_option("--checkpoint-file", a.checkpoint_file, "Checkpoint file (default: the output's name + .ckpt)");
  render->add_flag("--keep-checkpoint", a.keep_checkpoint,
                   "Keep the checkpoint when the render completes, so that --resume with a larger --spp extends it");
  render->add_flag("--resume", a.resume,
                   "Continue from the checkpoint; the result equals an uninterrupted render with the same settings");
  render->add_option("--texture-cache", a.texture_cache_mb,
                     "Memory for image texture tiles, in MB (default: 1024); the image does not depend on it")
      ->check(lantern::cli::number_in(1.0, 1048576.0, true, "a number of megabytes from 1 to 1048576"));
  render->add_option("--texture-dir", a.texture_dir,
                     "Where images are prepared as tiled, MIP-mapped textures (default: ~/.cache/lantern/textures)");
  render->add_option("--trace", a.trace,
                     "Write a timeline of the render to FILE.json (Chrome trace events: open it in Perfetto or "
                     "chrome://tracing; docs/profiling.md)");
  render->add_option("--trace-waves", a.trace_waves,
                     "With --trace: keep the first N waves in full, later ones as counters only (default 1000; 0: all)")
      ->check(lantern::cli::integer_in(0, 9223372036854775807LL, "an integer of 0 or more"));
  render->add_option("--part", a.part,
                     "Render part K of N of the render's work into a part file (-o; default: the output's name + "
                     ".partKofN); `lantern merge` adds the parts into the image")
      ->check(lantern::cli::part_of());
  render->add_option("--display-server", a.display_server,
                     "Stream the image as it refines to a viewer speaking tev's protocol at HOST:PORT (tev "
                     "listens on 127.0.0.1:14158)");
  render->add_flag("-q,--quiet", a.quiet, "No progress line or summary");
  CompareArgs ca;
  CLI::App* compare = app.add_subcommand("compare", "Error metrics of an image against a reference");
  compare->add_option("image", ca.a, "Image to measure")->required()->check(CLI::ExistingFile);
  compare->add_option("reference", ca.ref, "Reference image")->required()->check(CLI::ExistingFile);
  compare->add_option("--error-image", ca.error_image,
                      "Write a false-colour map of the relative squared error, with its scale as a bar below");
  compare->add_flag("--json", ca.json, "Print the metrics as one JSON object");
  compare->add_option("--error-scale", ca.error_scale, "Relative squared error shown as full red")
      ->check(lantern::cli::number_in(0.0, HUGE_VAL, false, "a positive number"));
  lantern::MergeArgs ma;
  CLI::App* merge = app.add_subcommand("merge", "Add the part files of a render (render --part K/N) into its image");
  merge->add_option("parts", ma.parts, "Part files, in any order")->required();
  merge->add_option("-o,--output", ma.output, "Output image (.exr, .png)")->required();
  merge->add_flag("--preview", ma.preview,
                  "Merge an incomplete set (missing or unfinished parts): each pixel normalised by its own samples");
  merge->add_flag("-q,--quiet", ma.quiet, "No summary");
  lantern::ViewArgs va;
  CLI::App* view = app.add_subcommand("view", "Show a render refining in a window; keys move the camera, F1 saves, R reloads (docs/viewer.md)");
  view->add_option("scene", va.scene, "Scene file (pbrt-v4 format)")->required();
  lantern::cli::add_render_request_options(*view, va.req);
  view->add_option("--screenshot", va.screenshot,
                   "F1 writes PREFIX-N.exr and PREFIX-N.png (default: the scene's output name + \"-view\")");
  view->add_option("--exposure", va.exposure, "Display exposure (a factor; + and - double and halve it)")
      ->check(lantern::cli::number_in(0.0, HUGE_VAL, false, "a positive number"));
  view->add_option("--texture-cache", va.texture_cache_mb, "Memory for image texture tiles, in MB (default: 1024)")
      ->check(lantern::cli::number_in(1.0, 1048576.0, true, "a number of megabytes from 1 to 1048576"));
  view->add_option("--texture-dir", va.texture_dir, "Where images are prepared as tiled, MIP-mapped textures");
  std::string info_image;
  CLI::App* info = app.add_subcommand("info", "Print an image's size and the settings it was rendered with, or those "
                                              "of a checkpoint or part file and the work it holds");
  info->add_option("image", info_image, "Image, checkpoint or part file written by lantern render")
      ->required()
      ->check(CLI::ExistingFile);
  app.set_version_flag("--version", lantern::version_line());
  if (const int code = lantern::cli::parse_command_line(app, argc, argv); code >= 0) return code == 0 ? 0 : fail(code);
  try {
    if (compare->parsed()) return run_compare(ca);
    if (info->parsed()) return run_info(info_image);
    if (merge->parsed()) return lantern::run_merge(ma, g_provenance);
    if (view->parsed()) {
#ifdef LANTERN_HAVE_VIEWER
      return lantern::run_view(va, g_provenance);
#else
      std::cerr << "error: this build has no viewer: GLFW was not found when it was configured (install "
                   "libglfw3-dev, or run scripts/install-deps.sh, and configure again)\n";
      return 1;
#endif
    }
    return run_render(a);
  } catch (const lantern::InputError& e) {
    std::cerr << e.what() << "\n";
    return fail(2);
  } catch (const std::exception& e) {
    std::cerr << "error: " << e.what() << "\n";
    return fail(1);
  }
}
