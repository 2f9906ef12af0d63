// `lantern merge PARTS... -o IMAGE`: the image of a render made in parts.
#pragma once

#include <string>
#include <vector>

namespace lantern {

struct MergeArgs {
  std::vector<std::string> parts;
  std::string output;
  bool preview = false;
  bool quiet = false;
};

// Exit status: 0 written, 1 the image could not be written (a rescue copy
// may have been), InputErrors propagate (exit 2 in main).
struct Provenance;
int run_merge(const MergeArgs& args, const Provenance& provenance);

}  // namespace lantern
