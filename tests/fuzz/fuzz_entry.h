// One fuzz input through the scene loader, the PLY reader or the NanoVDB
// reader. Shared by the
// libFuzzer targets (fuzz_pbrt, fuzz_ply) and by the replay test that runs
// the seed corpus and every saved crash in the ordinary test suite.
//
// A clear InputError is the expected answer to bad input and is swallowed;
// anything else (another exception, a crash, a sanitizer report, a leak, an
// allocation past libFuzzer's limit) is a bug.
#pragma once

#include <cstddef>
#include <cstdint>

namespace lantern::fuzz {

void load_pbrt(const uint8_t* data, size_t size);
void load_ply(const uint8_t* data, size_t size);
// NanoVDB file bytes through the nanovdb medium's reader, then a few rays
// through the grid it read.
void load_nvdb(const uint8_t* data, size_t size);

}  // namespace lantern::fuzz
