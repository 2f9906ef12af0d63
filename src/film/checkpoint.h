// Checkpoint files: the film's raw sums plus the position in the sample
// sequence, so that a stopped render continues exactly where it stopped.
//
// Layout (little-endian, as the machine writes it):
//   "LNTNCKPT" u32 version
//   u32 length, bytes: the fingerprint (key=value lines)
//   u32 pass_first, u32 wave, f64 elapsed_seconds
//   the film state (Film::write_state)
//   u64 FNV-1a hash of every byte before it
// Written to a temporary name and renamed, so a crash mid-write leaves the
// previous checkpoint intact.
#pragma once

#include <cstdint>
#include <string>

#include "film/film.h"

namespace lantern {

// Where a render is in its fixed sequence of (pass, wave): every wave before
// it has been merged into the film, none after it.
struct SequencePosition {
  uint32_t pass_first = 0;  // first sample index of the current pass
  uint32_t wave = 0;        // next wave of that pass
};

struct CheckpointInfo {
  std::string fingerprint;  // everything that shapes the sample sequence
  SequencePosition position;
  double elapsed_seconds = 0.0;  // render time spent so far, over all runs
};

void write_checkpoint(const std::string& path, const CheckpointInfo& info, const Film& film);

// Restores `film` (already sized for this render) and returns the saved
// info. Throws InputError naming the file for a missing, damaged or
// foreign file, and for a fingerprint that differs from `expected`, naming
// the first setting that differs.
CheckpointInfo read_checkpoint(const std::string& path, const std::string& expected_fingerprint, Film& film);

}  // namespace lantern
