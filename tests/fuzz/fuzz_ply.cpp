// libFuzzer target: PLY bytes (ASCII or binary) through the PLY reader.
#include "fuzz_entry.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  lantern::fuzz::load_ply(data, size);
  return 0;
}
