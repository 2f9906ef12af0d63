#!/usr/bin/env bash
# Renders scenes with Lantern and, if given, pbrt-v4, and prints both means
# and their ratio. Each scene names its pbrt-v4 output "<name>-pbrt.exr".
#   perf/compare-pbrt.sh LANTERN [PBRT] OUT_DIR SCENE.pbrt...
set -euo pipefail
LANTERN=$(realpath "$1"); shift
PBRT=""
if [ $# -gt 1 ] && [ -x "$1" ]; then PBRT=$(realpath "$1"); shift; fi
OUT=$1; shift
mkdir -p "$OUT"
for path in "$@"; do
  scene=$(basename "$path" .pbrt)
  cp "$path" "$OUT/"
  echo "== $scene"
  (cd "$OUT" && "$LANTERN" render $scene.pbrt --quiet -o $scene-lantern.exr > /dev/null)
  if [ -n "$PBRT" ]; then
    (cd "$OUT" && "$PBRT" --quiet $scene.pbrt > /dev/null 2>&1)
    "$LANTERN" compare "$OUT/$scene-lantern.exr" "$OUT/$scene-pbrt.exr" | grep -E "^(mean|mean_ref|ratio|relmse) "
  fi
done
