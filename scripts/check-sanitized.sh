#!/usr/bin/env bash
# The whole test suite under AddressSanitizer + UndefinedBehaviorSanitizer
# (and LeakSanitizer), built with clang in a build folder of its own, then
# each libFuzzer target for a bounded time.
#   scripts/check-sanitized.sh [BUILD_DIR] [FUZZ_SECONDS_PER_TARGET]
# With 0 seconds the fuzzers are neither built nor run, and nothing carries
# their coverage instrumentation (a tenth off the build and the tests); the
# suite's FuzzReplay tests still run every seed and saved crash.
set -euo pipefail
cd "$(dirname "$0")/.."
build="${1:-build-san}"
seconds="${2:-30}"
# A unity build: the instrumented headers are parsed a few times rather than
# once per file, which takes a quarter off this build's time.
fuzz=ON
[ "$seconds" = 0 ] && fuzz=OFF
# The RGB-to-spectrum table is the Release build's when there is one
# (fitting it again costs this build 15 core-seconds).
table=""
[ -f build/src/srgb-spectrum.table ] && table="-DLANTERN_RGB_TABLE=$PWD/build/src/srgb-spectrum.table"
# The Python module and the viewer are left out: the interpreter and the
# OpenGL driver they would load are not built with the sanitizers (the
# Release suite tests both).
# Line tables are all the reports' stack traces need: full debug
# information made this build a good part slower to compile and link.
cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_COMPILER=clang++ \
  "-DCMAKE_CXX_FLAGS_RELWITHDEBINFO=-O2 -gline-tables-only -DNDEBUG" \
  -DLANTERN_SANITIZE=ON -DLANTERN_FUZZ=$fuzz -DLANTERN_BUILD_PERF=OFF -DLANTERN_PYTHON=OFF -DLANTERN_VIEW=OFF -DCMAKE_UNITY_BUILD=ON $table
# The test programs only (and the fuzzers when they run): the command's own
# code is the Release suite's (cli_end_to_end, batch_cli, mpi_end_to_end);
# its build and batch_cli's renders cost this suite a minute.
if [ "$fuzz" = ON ]; then
  cmake --build "$build"
else
  cmake --build "$build" --target lantern_tests lantern_image_tests
fi
# Any report fails the test that triggered it. But one: OpenImageIO 2.4's
# TextureSystem::destroy deletes its implementation through the interface
# type, which ASan reports as a new/delete size mismatch inside the library.
export ASAN_OPTIONS=halt_on_error=1:detect_leaks=1:new_delete_type_mismatch=0
export UBSAN_OPTIONS=halt_on_error=1:print_stacktrace=1
# The statistical comparisons on a quarter of their samples: the memory and
# UB checks need the code paths, not the precision the Release suite has.
export LANTERN_TEST_SPP_SCALE=0.25
# LeakSanitizer's own tracer segfaults while it scans the dynamic
# thread-local storage of the libraries OpenImageIO loads ("Tracer caught
# signal 11", google/sanitizers#1353): on some machines now and then, on
# others after every test that reads an image. So it does not scan
# thread-local storage (use_tls=0), and what those libraries keep per
# thread is suppressed by library (scripts/lsan.supp). A failed test still
# runs once more; a real failure fails both times.
export LSAN_OPTIONS=use_tls=0:print_suppressions=0:suppressions=$(pwd)/scripts/lsan.supp
# Not here, to keep this suite short: the MPI job (Open MPI's libraries
# are not instrumented, and the test checks how ranks coordinate), the
# install (it copies files) and the command line's scripts (the command is
# not built here; signals, checkpoints, parts, batch use): the Release suite
# runs them.
# Nor the conformance suite (not even built here, tests/CMakeLists.txt):
# its scenes' region means against pbrt-v4's need the Release suite's
# samples, and the code they run (the parser, the constructs, the image
# decoders) runs here in the tests of each construct.
ctest --test-dir "$build" --output-on-failure -j"$(nproc)" --repeat until-pass:2 \
  -E '^(mpi_end_to_end|install_relocatable|cli_end_to_end|batch_cli)$'
if [ "$fuzz" = ON ]; then tests/fuzz/run.sh "$build" "$seconds"; fi
