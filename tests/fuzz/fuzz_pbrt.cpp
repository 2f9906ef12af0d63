// libFuzzer target: pbrt scene text through the parser, the scene builder
// and the light BVH.
#include "fuzz_entry.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  lantern::fuzz::load_pbrt(data, size);
  return 0;
}
