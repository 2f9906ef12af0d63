#!/usr/bin/env bash
# Runs each libFuzzer target for a bounded time on the seed corpus.
#   tests/fuzz/run.sh BUILD_DIR [SECONDS_PER_TARGET]
# BUILD_DIR must be configured with -DLANTERN_FUZZ=ON (clang). The corpus
# grows in BUILD_DIR/fuzz-corpus, never in the source tree. A crash input is
# written to BUILD_DIR/fuzz-crashes and the script fails; copy it into
# tests/fuzz/regressions/<target>/ once it is fixed, so it stays tested.
set -euo pipefail
src="$(cd "$(dirname "$0")/../.." && pwd)"
build="$(cd "$1" && pwd)"
seconds="${2:-30}"
mkdir -p "$build/fuzz-crashes"
for target in pbrt ply nvdb; do
  corpus="$build/fuzz-corpus/$target"
  mkdir -p "$corpus"
  cp -n "$src/tests/fuzz/corpus/$target/"* "$corpus/"
  # NanoVDB seeds are mostly an empty node table: stored compressed
  for gz in "$corpus"/*.gz; do [ -e "$gz" ] && gunzip -f "$gz"; done
  if [ "$target" = pbrt ]; then cp -n "$src/scenes/"*.pbrt "$corpus/"; fi
  cp -n "$src/tests/fuzz/regressions/$target/"* "$corpus/" 2>/dev/null || true
  echo "fuzzing $target for ${seconds}s ($(ls "$corpus" | wc -l) inputs in the corpus)"
  # -rss_limit_mb and -malloc_limit_mb make "bounded memory" a failure
  # condition; -timeout makes a hang one.
  log="$build/fuzz-$target.log"
  if ! (cd "$build/fuzz-crashes" && "$build/tests/fuzz_$target" -max_total_time="$seconds" -timeout=10 \
          -rss_limit_mb=2048 -malloc_limit_mb=1024 $( [ -f "$src/tests/fuzz/$target.dict" ] && echo -dict="$src/tests/fuzz/$target.dict") -print_final_stats=1 \
          "$corpus" >"$log" 2>&1); then
    tail -n 60 "$log"
    echo "fuzz_$target failed; the input is in $build/fuzz-crashes"
    exit 1
  fi
  grep -E "^stat::(number_of_executed_units|peak_rss_mb)|^#[0-9]+ +DONE" "$log" || true
done
