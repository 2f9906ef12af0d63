// Film files: the film's raw fixed-point sums plus the set of units merged
// into them. The same format serves checkpoints (a stopped render continues
// with the units it lacks), --part files (one share of a render, added up by
// `lantern merge`) and MPI ranks' checkpoints.
//
// Layout (little-endian, as the machine writes it):
//   "LNTNCKPT" u32 version
//   u32 length, bytes: the fingerprint (key=value lines)
//   u32 share index, u32 share count, u64 passes (0: open-ended, a time
//   budget), u32 waves per pass, f64 elapsed_seconds
//   u32 n, then n (u64 first, u64 end): the units done, sorted and disjoint
//   the film state (Film::write_state)
//   version 7 only: u64 length, bytes: what the integrator learnt (a
//   guiding field, GuidingField::save), opaque here (versions 3 to 6 held
//   guiding fields of earlier layouts: refused)
//   u64 FNV-1a hash of every byte before it
// Written to a temporary name and renamed, so a crash mid-write leaves the
// previous checkpoint intact.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "film/film.h"
#include "film/unit_set.h"

namespace lantern {

struct CheckpointInfo {
  std::string fingerprint;  // everything that shapes the sample sequence
  UnitShare share;          // the units this file's render was given
  uint64_t passes = 0;      // of the whole render; 0: open-ended (a time budget)
  uint32_t waves = 0;       // per pass; unit = pass * waves + wave
  UnitSet done;             // the units merged into the film
  double elapsed_seconds = 0.0;  // render time spent so far, over all runs
  std::string learnt;       // what the integrator learnt from the units done; most learn nothing
};

void write_checkpoint(const std::string& path, const CheckpointInfo& info, const Film& film);

// Restores `film` (already sized for this render) and returns the saved
// info. Throws InputError naming the file for a missing, damaged or
// foreign file, and for a fingerprint that differs from `expected`, naming
// the first setting that differs.
CheckpointInfo read_checkpoint(const std::string& path, const std::string& expected_fingerprint, Film& film);

// The files of a checkpoint's pieces that exist: path, then path.rank*.
std::vector<std::string> checkpoint_pieces(const std::string& path);
// A checkpoint may be in pieces: FILE (one process) and FILE.rank<r> (one
// per MPI rank). Reads every piece of `path` into `film` (sized for the
// render) and returns their union: the units of all, the sums of all, the
// longest elapsed time. A piece whose units another piece holds entirely was
// absorbed by it (a resumed rank 0 takes in all pieces and saves them first)
// and is skipped; pieces that share only some units are refused, naming
// both. `pieces` receives every file read, skipped ones too.
// Pieces that each hold what their process learnt are joined by
// `join_learnt` (the integrator's: GuidingField::restore_joined), which
// throws std::runtime_error for states that do not fit together; without
// it such pieces are refused.
using JoinLearnt = std::function<std::string(const std::vector<std::string>& learnt)>;
CheckpointInfo read_checkpoint_pieces(const std::string& path, const std::string& expected_fingerprint, Film& film,
                                      std::vector<std::string>& pieces, const JoinLearnt& join_learnt = {});

// The first key=value line where two fingerprints differ: that line of
// each ("(nothing)" where one has no more lines); two empty strings when
// they are equal.
std::pair<std::string, std::string> fingerprint_difference(const std::string& a, const std::string& b);

// Reads any film file into `film` (0x0: it takes the file's size) without
// comparing fingerprints; `lantern merge` compares them across its parts.
CheckpointInfo read_film_file(const std::string& path, Film& film);
// The fingerprint a checkpoint or film file was made with (its header
// only). Throws InputError as read_checkpoint does for a missing, foreign
// or damaged header.
std::string read_checkpoint_fingerprint(const std::string& path);

}  // namespace lantern
