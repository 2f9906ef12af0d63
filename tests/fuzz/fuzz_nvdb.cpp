// libFuzzer target: NanoVDB file bytes through the nanovdb medium's reader.
#include "fuzz_entry.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  lantern::fuzz::load_nvdb(data, size);
  return 0;
}
