#include "integrator/render_checkpoints.h"

#include <filesystem>
#include <new>
#include <stdexcept>
#include <vector>

#include "lantern/error.h"
#include "sampler/sampler.h"

namespace lantern {

std::string own_checkpoint_piece(const RenderOptions& o) {
  return o.checkpoint_rank < 0 ? o.checkpoint_path : o.checkpoint_path + ".rank" + std::to_string(o.checkpoint_rank);
}

std::string sequence_fingerprint(const RenderOptions& o, const ImageRegion& region) {
  std::string f;
  auto line = [&](const std::string& k, const std::string& v) { f += k + "=" + v + "\n"; };
  line("scene", o.checkpoint_key);
  line("integrator", name(o.integrator));
  if (o.spectral) line("colour", "spectral");  // (RGB renders keep the fingerprint they always had)
  if (!traces_paths(o.integrator)) line("mis", name(o.mis));
  if (merges_vertices(o.integrator)) {
    line("vcm", std::to_string(o.vcm_radius) + " " + std::to_string(o.vcm_alpha));
    line("passes", "one sample per pixel, waves of equal size");  // (since merging renders were planned so)
  }
  line("maxdepth", std::to_string(o.maxdepth));
  // (only off pbrt-v4's rule: renders from before the scale existed keep
  // their fingerprint, and resume with --roulette 1)
  if (scales_roulette(o.integrator) && o.roulette_scale != 1.f) line("roulette", exact_text(o.roulette_scale));
  // (likewise: bdpt from before the rate existed resumes with --light-subpaths 1)
  if (uses_light_subpath_rate(o.integrator) && o.light_subpath_rate != 1.f)
    line("light-subpaths", light_subpaths_text(o.light_subpath_rate));
  // (the camera samples' layout; renders from before splitting resume with --split 1)
  // Under a time budget a pass is one camera sample, so the units number
  // by the split, which `auto`'s pilot chooses again on resume: its second
  // weighing of pixels (split_choice.cpp) may choose otherwise than the
  // first did, so timed renders it chose for say so.
  if (splits_camera_samples(o.integrator) && o.split != 1)
    line("split", split_text(o.split) + (o.split == kSplitAuto && o.time_limit_seconds > 0 ? " (pilot 2)" : ""));
  line("seed", std::to_string(o.seed));
  line("light-sampler", name(o.light_sampler));
  // (auto, the default, keeps the fingerprint of renders from before the
  // choice existed: every choice leaves the same image, and a resumed
  // render's pilot chooses again as the first did)
  if (o.light_choice != LightChoiceKind::Auto) line("light-choice", name(o.light_choice));
  line("sampler", std::string(name(o.sampler.type)) + " " + o.sampler.randomization + " " + std::to_string(o.sampler.seed) + " " +
                      std::to_string(o.sampler.xsamples) + "x" + std::to_string(o.sampler.ysamples) +
                      (o.sampler.jitter ? " jitter" : ""));
  line("resolution", std::to_string(region.width) + "x" + std::to_string(region.height));
  if (region.cropped())
    line("crop", "from " + std::to_string(region.x0) + "," + std::to_string(region.y0) + " of " +
                     std::to_string(region.full_width) + "x" + std::to_string(region.full_height));
  line("budget", o.time_limit_seconds > 0 ? std::string("time") : "spp " + std::to_string(o.spp));
  if (o.target_error > 0) line("target-error", std::to_string(o.target_error));  // adaptive passes
  else if (o.adaptive) line("adaptive", "budget");
  // Guided renders: passes of one sample while the field learns, an
  // unguided render's after (integrator/pass_layout.h); "1" was one sample
  // per pass to the end, whose units number otherwise. Under "2" so were
  // adaptive renders' (merging renders' still are: no second layout), and
  // the path tracer's camera samples split after it only where the guide
  // had stopped (under a time budget, passes of a camera sample number
  // their units by the split).
  const bool relaid_adaptive = (o.target_error > 0 || o.adaptive) && !merges_vertices(o.integrator);
  const bool split_beside_guide = splits_camera_samples(o.integrator) && o.split != 1;
  const char* guided_layout = relaid_adaptive || split_beside_guide ? "3" : "2";
  if (o.guiding) line("guiding", guided_layout);
  if (o.guide_light_subpaths) line("guide-light", guided_layout);
  if (o.any_guiding()) line("guide-distribution", name(o.guide_distribution));  // (lobes are not quadtrees)
  if (o.any_guiding() && !o.guide_stop) line("guide-stop", "never");
  if (o.gbuffer) line("gbuffer", "1");  // the film sums the samples' squares too
  if (o.spectral_buckets > 0)  // uniform wavelengths, and the film keeps the buckets
    line("spectral-buckets", std::to_string(o.spectral_buckets) + " over " + std::to_string(o.spectral_lambda_min) +
                                 "-" + std::to_string(o.spectral_lambda_max) + " nm");
  line("wave-size", std::to_string(o.wave_size));
  line("rays", name(o.ray_backend));
  return f;
}

std::string fingerprint_value(const std::string& f, const std::string& key) {
  const std::string lines = "\n" + f, head = "\n" + key + "=";
  const size_t at = lines.find(head);
  if (at == std::string::npos) return "";
  const size_t from = at + head.size(), end = lines.find('\n', from);
  return lines.substr(from, end == std::string::npos ? std::string::npos : end - from);
}

std::string resumed_fingerprint(const RenderOptions& o) {
  if (!o.resume) return "";
  const std::vector<std::string> pieces = checkpoint_pieces(o.checkpoint_path);
  return pieces.empty() ? "" : read_checkpoint_fingerprint(pieces[0]);
}

namespace {

// A fingerprint's "budget=" line, and the fingerprint without it.
std::string budget_line(const std::string& f) { return fingerprint_value(f, "budget"); }
std::string without_budget(const std::string& f) {
  const size_t at = f.find("\nbudget=");
  if (at == std::string::npos) return f;
  const size_t end = f.find('\n', at + 1);
  return f.substr(0, at) + (end == std::string::npos ? "" : f.substr(end));
}

}  // namespace

std::string extension_refusal(const std::string& saved, const std::string& now, const RenderOptions& o, int width,
                              int height) {
  if (without_budget(saved) != without_budget(now)) return "it belongs to another render";
  const std::string was = budget_line(saved), is = budget_line(now);
  if (was == "time" || is == "time")
    return "a time budget and a sample budget do not continue each other (resume with the budget it was made with)";
  if (o.target_error > 0 || o.adaptive) return "adaptive sampling plans its passes from the image so far: resume with the same --spp";
  if (o.any_guiding()) return "guided paths learn in iterations planned from the budget: resume with the same --spp";
  const uint32_t old_spp = uint32_t(std::stoul(was.substr(was.find(' ') + 1))), new_spp = uint32_t(o.spp);
  if (new_spp < old_spp)
    return "it holds " + std::to_string(old_spp) + " samples per pixel, more than this render's " +
           std::to_string(new_spp);
  // Its units must be whole units of this render, of the same samples.
  const bool merging = merges_vertices(o.integrator);
  const uint32_t old_pass = merging ? 1u : std::min(old_spp, 16u), new_pass = merging ? 1u : std::min(new_spp, 16u);
  if (old_pass != new_pass)
    return "its passes are of " + std::to_string(old_pass) + " samples per pixel and this render's of " +
           std::to_string(new_pass) + " (a render of fewer than 16 spp continues only to its own budget)";
  if (old_spp % old_pass != 0)
    return "its last pass is short (" + std::to_string(old_spp) + " is not a multiple of " + std::to_string(old_pass) +
           ")";
  const SamplerSpec a = make_sampler_spec(o.sampler, width, height, old_spp, o.seed),
                    b = make_sampler_spec(o.sampler, width, height, new_spp, o.seed);
  // (Only zsobol and paddedsobol read the block size: the other samplers'
  // samples depend on the pixel and the sample's index alone.)
  const bool blocks = o.sampler.type == SamplerKind::ZSobol || o.sampler.type == SamplerKind::PaddedSobol;
  if (blocks && (a.log2_spp != b.log2_spp || a.index_bits != b.index_bits))
    return std::string("the ") + name(o.sampler.type) + " sampler lays out each pixel's samples for the planned count "
           "rounded up to a power of two (" + std::to_string(1u << a.log2_spp) + " then, " +
           std::to_string(1u << b.log2_spp) + " now), so a " + std::to_string(old_spp) + "-spp render's samples are "
           "not the first of a " + std::to_string(new_spp) + "-spp one: extend it to at most " +
           std::to_string(1u << a.log2_spp) + " spp, or render with halton, sobol or independent";
  return "";
}

CheckpointInfo start_checkpointing(const RenderOptions& opt, const RenderHooks& hooks, const std::string& fingerprint,
                                   Film& film, const JoinLearnt& join_learnt) {
  CheckpointInfo info;
  info.fingerprint = fingerprint;
  info.share = UnitShare{opt.share_index, opt.share_count};
  if (opt.resume && opt.resume_reads) {
    std::vector<std::string> pieces = checkpoint_pieces(opt.checkpoint_path);
    // A larger sample budget continues a render made with a smaller one
    // (finished with keep_checkpoint, or interrupted) when its samples are
    // the first ones of this render's.
    std::string expected = fingerprint;
    if (!pieces.empty()) {
      const std::string saved = read_checkpoint_fingerprint(pieces[0]);
      if (saved != fingerprint && without_budget(saved) == without_budget(fingerprint)) {
        const std::string why = extension_refusal(saved, fingerprint, opt, film.width(), film.height());
        if (!why.empty())
          throw InputError({pieces[0], 0, 0}, "the checkpoint (budget " + budget_line(saved) +
                                                  ") cannot be continued to budget " + budget_line(fingerprint) +
                                                  ": " + why);
        expected = saved;
      }
    }
    info = read_checkpoint_pieces(opt.checkpoint_path, expected, film, pieces, join_learnt);
    info.fingerprint = fingerprint;  // what this render's own checkpoints say
    if (info.share.index != opt.share_index || info.share.count != opt.share_count)
      throw InputError({opt.checkpoint_path, 0, 0},
                       "checkpoint was made for part " + std::to_string(info.share.index + 1) + "/" +
                           std::to_string(info.share.count) + ", this render is part " +
                           std::to_string(opt.share_index + 1) + "/" + std::to_string(opt.share_count));
    // The pieces read are in this film now: saved as this process's piece
    // first, then the others removed, so that no moment has them twice (a
    // resume skips a piece another holds entirely anyway). Before the other
    // processes hear of it (sync_checkpoint), so none of their new pieces
    // is taken for an old one.
    const std::string own = own_checkpoint_piece(opt);
    if (pieces.size() > 1 || pieces[0] != own) write_checkpoint(own, info, film);
    std::error_code ec;
    for (const std::string& piece : pieces)
      if (piece != own) std::filesystem::remove(piece, ec);
  } else if (!opt.resume && opt.resume_reads && !opt.checkpoint_path.empty()) {
    // A fresh render: pieces of an older one must not join a later resume.
    std::error_code ec;
    for (const std::string& piece : checkpoint_pieces(opt.checkpoint_path)) std::filesystem::remove(piece, ec);
  }
  if (hooks.sync_checkpoint && !opt.checkpoint_path.empty())
    hooks.sync_checkpoint(info.done, info.elapsed_seconds, info.learnt);
  return info;
}

void Checkpointer::write_to(const std::string& path, const Film& film) {
  info_.elapsed_seconds = elapsed();
  // (What was learnt goes to checkpoints, which a run resumes from; a
  // film file, which `lantern merge` adds up, has no use for it.)
  const bool checkpoint = path == own_path();
  if (learnt_ && checkpoint) info_.learnt = learnt_();
  else info_.learnt.clear();
  write_checkpoint(path, info_, film);
  last_ = Clock::now();
  if (hooks_.checkpoint_written && path == own_path()) hooks_.checkpoint_written();
}

GuidingField new_guiding_field(Vec3 lo, Vec3 hi, const RenderOptions& o) {
  GuidingSettings settings;
  if (o.guide_distribution == GuideModel::Vmm) settings.distribution = GuideDistributionKind::kMixture;
  settings.stop_where_unpaid = o.guide_stop;
  return GuidingField(lo, hi, o.time_limit_seconds > 0 ? 0 : uint64_t(o.spp), o.guiding, o.guide_light_subpaths,
                      settings);
}

JoinLearnt guiding_field_joiner(Vec3 lo, Vec3 hi, const RenderOptions& o) {
  if (!o.any_guiding()) return {};
  return [lo, hi, &o](const std::vector<std::string>& pieces) {
    GuidingField joined = new_guiding_field(lo, hi, o);
    joined.restore_joined(pieces);
    return joined.save();
  };
}

void resume_guiding(GuidingField& field, const Checkpointer& checkpoints, const RenderOptions& o) {
  if (checkpoints.done_before().empty()) return;
  try {
    if (checkpoints.learnt().empty()) throw std::runtime_error("it holds no guiding field");
    field.restore(checkpoints.learnt());
    if (!o.resume_reads) field.clear_learnt_sums();
  } catch (const std::bad_alloc&) {
    throw InputError({o.checkpoint_path, 0, 0},
                     "checkpoint cannot be resumed with guiding: its guiding field is "
                     "larger than memory holds");
  } catch (const std::runtime_error& e) {
    throw InputError({o.checkpoint_path, 0, 0}, std::string("checkpoint cannot be resumed with guiding: ") + e.what());
  }
}

}  // namespace lantern
