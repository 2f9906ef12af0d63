#include "app/command_line.h"

#include <cstdlib>
#include <algorithm>
#include <iostream>

#include "app/cli_checks.h"
#include "math/edit_distance.h"

namespace lantern::cli {

namespace {

// Every long and short flag of app, with its dashes.
std::vector<std::string> flag_names(const CLI::App& app) {
  std::vector<std::string> names;
  for (const CLI::Option* o : app.get_options()) {
    for (const std::string& n : o->get_lnames()) names.push_back("--" + n);
    for (const std::string& n : o->get_snames()) names.push_back("-" + n);
  }
  return names;
}

// The subcommand being parsed when the error came (the deepest one that
// was named), or app itself.
const CLI::App& active(const CLI::App& app) {
  for (const CLI::App* sub : app.get_subcommands())
    if (sub->parsed()) return active(*sub);
  return app;
}

void suggest(const CLI::App& app, int argc, char** argv) {
  const CLI::App& at = active(app);
  if (&at == &app && argc > 1 && argv[1][0] != '-') {  // an unknown subcommand
    std::vector<std::string> subs;
    for (const CLI::App* sub : app.get_subcommands([](const CLI::App*) { return true; })) subs.push_back(sub->get_name());
    const std::string near = closest(argv[1], subs);
    if (!near.empty()) std::cerr << "\"" << argv[1] << "\" is not a command; did you mean \"" << near << "\"?\n";
    return;
  }
  const std::vector<std::string> flags = flag_names(at);
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg.size() < 2 || arg[0] != '-' || (arg[1] >= '0' && arg[1] <= '9')) continue;
    const std::string flag = arg.substr(0, arg.find('='));
    if (std::find(flags.begin(), flags.end(), flag) != flags.end()) continue;
    const std::string near = closest(flag, flags);
    if (!near.empty()) std::cerr << "unknown option \"" << flag << "\"; did you mean \"" << near << "\"?\n";
  }
}

}  // namespace

std::string closest(const std::string& word, const std::vector<std::string>& candidates) {
  return nearest_word(word, candidates, std::max<size_t>(2, word.size() / 3));
}

int parse_command_line(CLI::App& app, int argc, char** argv) {
  try {
    app.parse(argc, argv);
    return -1;
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    app.exit(e);  // CLI11's message
    suggest(app, argc, argv);
    return 2;
  }
}

void add_render_request_options(CLI::App& c, RenderRequest& r) {
  CLI::Option* spp = c.add_option("--spp", r.spp, "Samples per pixel (default: the scene's Sampler pixelsamples)")->check(positive_integer());
  c.add_option("--time", r.time, "Render for this many seconds instead of a sample count")->check(positive_seconds())->excludes(spp);
  c.add_option("--target-error", r.target_error,
                     "Adaptive sampling: give pixels samples until the estimated relative MSE of each block of them "
                     "is below this (e.g. 0.001); --spp (default 65536) or --time limits it (docs/adaptive-sampling.md)")
      ->check(CLI::PositiveNumber);
  c.add_option("--integrator", r.integrator,
                     "Integrator: path, bdpt, lt (light tracing), vcm (vertex connection and merging), bpm "
                     "(bidirectional photon mapping), ppm (progressive photon mapping), directlighting (pbrt-v3's), ambientocclusion (pbrt-v4's) or mlt (Metropolis over bdpt; "
                     "--spp: its mutations per pixel); "
                     "default: the scene's Integrator")
      ->check(CLI::IsMember({"path", "bdpt", "lt", "vcm", "bpm", "ppm", "directlighting", "ambientocclusion", "mlt"}));
  c.add_option("--vcm-radius", r.vcm_radius,
                     "vcm, bpm, ppm: the merging radius of the first pass (default: an sppm Integrator's \"radius\", else 0.003 "
                     "of the scene's bounding radius)")
      ->check(CLI::PositiveNumber);
  c.add_option("--vcm-alpha", r.vcm_alpha, "vcm, bpm, ppm: the radius of pass i is radius * i^((alpha - 1) / 2); default 0.75")
      ->check(CLI::Range(0.01, 1.0));
  c.add_option("--roulette", r.roulette,
                     "path: Russian roulette keeps a path with probability min(1, S x its throughput) from the second "
                     "bounce on; 1 is pbrt-v4's rule; 0.01 to 100, default 2 (docs/performance.md)")
      ->check(CLI::Validator(
          [](std::string& text) {  // (CLI::Range lets nan through)
            const double v = std::strtod(text.c_str(), nullptr);
            return v >= 0.01 && v <= 100.0 ? std::string() : "Value " + text + " not in range 0.01 to 100";
          },
          "FLOAT in [0.01 - 100]"));
  c.add_option("--split", r.split,
               "path: N paths (1, 2, 4, 8 or 16) share each camera sample's first hit, its camera ray and next-event "
               "estimate; --spp counts paths. Pays where light that bounces makes the noise, not direct light. auto: "
               "chosen per scene by a short pilot that estimates each count's error at equal time "
               "(docs/splitting.md); default auto")
      ->check(CLI::IsMember({"auto", "1", "2", "4", "8", "16"}));
  c.add_option("--merging", r.merging,
               "vcm: auto (default): a short pilot estimates vcm's and bdpt's error at equal time, and where merges do "
               "not pay the render is bdpt's; on: merge whatever it pays (docs/vcm.md)")
      ->check(CLI::IsMember({"auto", "on"}));
  c.add_option("--light-subpaths", r.light_subpaths,
               "bdpt: the probability Q that a camera sample traces a light subpath beyond the light (0.01 to 1; 1 is "
               "pbrt-v4's bdpt; 0: none, the eye subpaths alone, as the path tracer), or auto: chosen per scene by a "
               "short pilot that estimates each rate's error at equal time (default; docs/bdpt.md)")
      ->check(CLI::Validator(
          [](std::string& text) {
            try {
              parse_light_subpaths(text);
              return std::string();
            } catch (const std::invalid_argument& e) {
              return std::string(e.what());
            }
          },
          "auto|FLOAT in [0.01 - 1]"));
  c.add_option("--mis", r.mis, "bdpt's MIS heuristic: power or balance")
      ->check(CLI::IsMember({"power", "balance"}));
  c.add_flag("--adaptive", r.adaptive,
                   "Adaptive sampling without a target: --spp (32 or more) is then the mean over the image, or --time "
                   "the budget, and samples go where the estimated error says they pay (docs/adaptive-sampling.md)");
  c.add_flag("--guide", r.guide,
                   "Path guiding: paths learn where light comes from and sample it (path, and the eye subpaths of bdpt and vcm; "
                   "docs/guiding.md)");
  c.add_flag("--guide-light", r.guide_light,
                   "bdpt, vcm: light subpaths learn where what leaves a surface reaches the image and sample it, the "
                   "emission directions of area lights too (with --guide, both subpaths are guided; docs/guiding.md)");
  c.add_option("--guide-distribution", r.guide_distribution,
               "What guided paths learn directions with: vmm (a mixture of von Mises-Fisher lobes, the default; "
               "docs/guiding-lobes.md) or quadtree (the SD-tree's; docs/guiding.md)")
      ->check(CLI::IsMember({name(GuideModel::Quadtree), name(GuideModel::Vmm)}));
  c.add_option("--guide-stop", r.guide_stop,
               "auto (the default): each guided field stops, for the rest of the render, at the end of a learning "
               "iteration whose records say its guide left more of the second moment the BSDF's directions alone "
               "would have than 0.9 (the third iteration) or 0.7 (a later one); never: guided to the end "
               "(docs/guiding-stop.md)")
      ->check(CLI::IsMember({"auto", "never"}));
  c.add_flag("--spectral", r.spectral,
                   "Render with sampled wavelengths, four per camera sample, as pbrt-v4 does, instead of in RGB "
                   "(docs/spectral.md)");
  c.add_option("--maxdepth", r.maxdepth, "Maximum path depth, as pbrt defines it (default: the scene's)")->check(integer_in(0, 2147483647, "an integer of 0 or more"));
  c.add_option("--threads", r.threads, "Worker threads (default: all cores)")->check(positive_integer());
  c.add_option("--seed", r.seed, "Random seed (0 or more)")
      ->check(integer_in(0, 9223372036854775807LL, "an integer of 0 or more"));
  c.add_option("--sampler", r.sampler,
                     "Sample pattern: zsobol, paddedsobol, sobol, halton, stratified or independent "
                     "(default: the scene's Sampler)")
      ->check(CLI::IsMember({"zsobol", "paddedsobol", "sobol", "halton", "stratified", "independent"}));
  c.add_option("--light-sampler", r.light_sampler,
                     "How next-event estimation chooses lights: bvh, power or uniform (default: the scene's "
                     "Integrator \"lightsampler\", else bvh)")
      ->check(CLI::IsMember({"bvh", "power", "uniform"}));
  c.add_option("--light-choice", r.light_choice,
               "How light subpaths choose their light: power (pbrt-v4's), uniform, or auto: for bdpt with "
               "--light-subpaths auto, chosen per scene with several lights by the same pilot, which also weighs "
               "choices it measures; otherwise power (default auto; docs/bdpt.md)")
      ->check(CLI::IsMember({"auto", "power", "uniform"}));
  c.add_option("--resolution", r.resolution, "Image size W H (default: the scene's Film)")->expected(2)->check(integer_in(1, 65536, "an integer from 1 to 65536"));
  CLI::Option* crop = c.add_option("--cropwindow", r.crop_window,
                                   "Render only this part of the image: x0,x1,y0,y1 in [0, 1] (pbrt-v4's flag; over the "
                                   "Film's cropwindow and pixelbounds)")
                          ->expected(4)
                          ->delimiter(',')
                          ->check(number_in(0.0, 1.0, true, "a number from 0 to 1"));
  CLI::Option* bounds = c.add_option("--pixelbounds", r.pixel_bounds,
                                     "Render only these pixels: x0,x1,y0,y1 (x1 and y1 excluded; pbrt-v4's flag)")
                            ->expected(4)
                            ->delimiter(',')
                            ->check(integer_in(0, 65536, "an integer from 0 to 65536"))
                            ->excludes(crop);
  c.add_option("--pixel", r.pixel, "Render only the pixel X,Y (0,0 the top left; pbrt-v4's flag)")
      ->expected(2)
      ->delimiter(',')
      ->check(integer_in(0, 65535, "an integer from 0 to 65535"))
      ->excludes(crop)
      ->excludes(bounds);
  // The region as a whole (its values in order), when the command line is
  // parsed: a usage error.
  c.parse_complete_callback([&r] {
    try {
      RenderOptions o;
      set_render_region(r, o);
    } catch (const std::invalid_argument& e) {
      throw CLI::ValidationError(e.what());
    }
  });
  c.add_option("--rays", r.rays, "Ray query back end: stream (Embree Np streams), stream-1m, single, packet16")
      ->check(CLI::IsMember({"stream", "stream-1m", "single", "packet16"}));
  c.add_option(
       "--wave-size", r.wave_size,
       "Paths per wave (default 4096; 16384 for vcm, bpm and ppm, whose eye vertices merge with the light vertices of "
       "their wave; for those, an sppm scene's photonsperiteration, by default a whole pass, at most 131072)")
      ->check(integer_in(1, 1 << 22, "an integer from 1 to 4194304"));
}

}  // namespace lantern::cli
