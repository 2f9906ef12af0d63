#include "integrator/render_checkpoints.h"

#include <filesystem>
#include <vector>

#include "lantern/error.h"

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
  if (o.integrator != Integrator::Path) line("mis", name(o.mis));
  if (merges_vertices(o.integrator)) {
    line("vcm", std::to_string(o.vcm_radius) + " " + std::to_string(o.vcm_alpha));
    line("passes", "one sample per pixel, waves of equal size");  // (since merging renders were planned so)
  }
  line("maxdepth", std::to_string(o.maxdepth));
  line("seed", std::to_string(o.seed));
  line("light-sampler", name(o.light_sampler));
  line("sampler", std::string(name(o.sampler.type)) + " " + o.sampler.randomization + " " + std::to_string(o.sampler.seed) + " " +
                      std::to_string(o.sampler.xsamples) + "x" + std::to_string(o.sampler.ysamples) +
                      (o.sampler.jitter ? " jitter" : ""));
  line("resolution", std::to_string(region.width) + "x" + std::to_string(region.height));
  if (region.cropped())
    line("crop", "from " + std::to_string(region.x0) + "," + std::to_string(region.y0) + " of " +
                     std::to_string(region.full_width) + "x" + std::to_string(region.full_height));
  line("budget", o.time_limit_seconds > 0 ? std::string("time") : "spp " + std::to_string(o.spp));
  if (o.target_error > 0) line("target-error", std::to_string(o.target_error));  // adaptive passes
  if (o.guiding) line("guiding", "1");  // one sample per pass, guided directions
  line("wave-size", std::to_string(o.wave_size));
  line("rays", name(o.ray_backend));
  return f;
}

CheckpointInfo start_checkpointing(const RenderOptions& opt, const RenderHooks& hooks, const std::string& fingerprint,
                                   Film& film) {
  CheckpointInfo info;
  info.fingerprint = fingerprint;
  info.share = UnitShare{opt.share_index, opt.share_count};
  if (opt.resume && opt.resume_reads) {
    std::vector<std::string> pieces;
    info = read_checkpoint_pieces(opt.checkpoint_path, fingerprint, film, pieces);
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
  if (hooks.sync_checkpoint && !opt.checkpoint_path.empty()) hooks.sync_checkpoint(info.done, info.elapsed_seconds);
  return info;
}

void Checkpointer::write_to(const std::string& path, const Film& film) {
  info_.elapsed_seconds = elapsed();
  write_checkpoint(path, info_, film);
  last_ = Clock::now();
  if (hooks_.checkpoint_written && path == own_path()) hooks_.checkpoint_written();
}

}  // namespace lantern
