// What a render keeps of itself between runs: checkpoints written from the
// film's merging thread, the fingerprint that decides which checkpoint may
// continue which render, and the units a resumed run starts with.
#pragma once

#include <chrono>
#include <functional>
#include <string>

#include "film/checkpoint.h"
#include "integrator/guiding_field.h"
#include "integrator/render_settings.h"
#include "lantern/render.h"

namespace lantern {

// Everything that decides which samples a render takes and the order the
// film sums them in: a checkpoint continues only a render that agrees on
// all of it. Thread count is not here: it changes neither.
std::string sequence_fingerprint(const RenderOptions& o, const ImageRegion& region);
// A fingerprint's value for `key` ("" when it has no such line).
std::string fingerprint_value(const std::string& fingerprint, const std::string& key);
// The fingerprint of the checkpoint a resumed render continues ("": not
// resumed, or no checkpoint yet).
std::string resumed_fingerprint(const RenderOptions& o);

// Why a checkpoint made with fingerprint `saved` cannot be continued by a
// render with fingerprint `now` and options `o` ("" when it can): they must
// differ in the sample budget only, the new one the larger, each unit of
// the old render a whole unit of the new one (passes of one size, the last
// one full), and the sampler's layout of a pixel's samples the same.
std::string extension_refusal(const std::string& saved, const std::string& now, const RenderOptions& o, int width,
                              int height);

// This process's piece of the checkpoint.
std::string own_checkpoint_piece(const RenderOptions& o);

// The units already in the film when this run starts: none, or those of
// the checkpoint's pieces (read here, or passed on by the process that
// read them, through hooks.sync_checkpoint), the time they took and what
// they learnt (pieces that each learnt joined by `join_learnt`).
CheckpointInfo start_checkpointing(const RenderOptions& opt, const RenderHooks& hooks, const std::string& fingerprint,
                                   Film& film, const JoinLearnt& join_learnt = {});

// Writes checkpoints from the merge stage: the one place that sees the film
// between two waves.
class Checkpointer {
 public:
  using Clock = std::chrono::steady_clock;
  // A process that did not read the checkpoint (an MPI rank but the
  // first) was told the units done, but its film holds none of them: its
  // pieces list only the units it renders, so that they fit together with
  // the reading process's pieces on the next resume.
  Checkpointer(const RenderOptions& o, const RenderHooks& hooks, CheckpointInfo info, Clock::time_point start)
      : opt_(o),
        hooks_(hooks),
        info_(std::move(info)),
        before_(info_.done),
        start_(start),
        last_(start),
        prior_seconds_(info_.elapsed_seconds) {
    if (!o.resume_reads) info_.done = UnitSet{};
  }
  bool enabled() const { return !opt_.checkpoint_path.empty(); }
  std::string own_path() const { return own_checkpoint_piece(opt_); }
  double elapsed() const { return prior_seconds_ + std::chrono::duration<double>(Clock::now() - start_).count(); }
  // The units in this process's film, and those of every process when
  // this run began (which it does not render again).
  UnitSet& done() { return info_.done; }
  const UnitSet& done_before() const { return before_; }
  void set_units(uint64_t passes, uint32_t waves) {
    info_.passes = passes;
    info_.waves = waves;
  }
  // What the integrator learnt, to be saved with the film (a guiding
  // field): asked for at each write, from the merge stage, so that it
  // belongs to the same units as the film. And what a resumed run read.
  void learns(std::function<std::string()> state) { learnt_ = std::move(state); }
  const std::string& learnt() const { return info_.learnt; }
  void maybe_write(const Film& film) {
    if (enabled() && opt_.checkpoint_seconds > 0 &&
        std::chrono::duration<double>(Clock::now() - last_).count() >= opt_.checkpoint_seconds)
      write(film);
  }
  void write(const Film& film) { write_to(own_path(), film); }
  void write_to(const std::string& path, const Film& film);

 private:
  const RenderOptions& opt_;
  const RenderHooks& hooks_;
  CheckpointInfo info_;
  const UnitSet before_;
  std::function<std::string()> learnt_;
  Clock::time_point start_, last_;
  double prior_seconds_;
};

// A guided render's field, on the schedule its budget plans.
GuidingField new_guiding_field(Vec3 lo, Vec3 hi, const RenderOptions& o);
// For start_checkpointing: joins the pieces of a guided render's field that
// MPI's ranks each saved (GuidingField::restore_joined); none for renders
// that do not guide.
JoinLearnt guiding_field_joiner(Vec3 lo, Vec3 hi, const RenderOptions& o);
// A resumed guided render goes on with the field its units learnt. Of
// processes that share their sums (MPI's ranks), the one that read the
// checkpoint keeps the sums it holds and the others start from the shared
// field alone, so that the next exchange counts them once. Throws
// InputError for a checkpoint whose field cannot be taken.
void resume_guiding(GuidingField& field, const Checkpointer& checkpoints, const RenderOptions& o);

}  // namespace lantern
