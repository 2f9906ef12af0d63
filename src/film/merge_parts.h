// `lantern merge`: adds the film files of a render's parts (--part K/N)
// into the film of the whole render. The sums are fixed-point, so the
// merged film equals the single-process film bit for bit.
#pragma once

#include <string>
#include <vector>

#include "film/checkpoint.h"
#include "film/film.h"

namespace lantern {

struct MergedParts {
  Film film;
  std::string fingerprint;  // the parts' common one
  uint32_t parts = 0;       // N of K/N
  UnitSet done;             // all units of all parts given
  bool complete = false;    // every part present and finished
  std::vector<std::string> missing;  // with preview: what the image lacks, in words
};

// Refuses, with an InputError naming the file: a file that is not a part
// (or is damaged); a part of another render (another scene, seed,
// resolution, integrator or any setting in the fingerprint), naming the
// setting; parts of splits into different N; the same part twice. Without
// `preview`, also a missing part and an unfinished (interrupted) one
// (std::runtime_error, naming the part and the unfinished part's file);
// with it, those are listed in `missing` and the film holds what there is,
// each pixel normalised by its own sample count.
MergedParts merge_parts(const std::vector<std::string>& paths, bool preview);

}  // namespace lantern
