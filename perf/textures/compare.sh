#!/usr/bin/env bash
# Renders perf/textures/textures.pbrt (every texture class and mapping) with
# Lantern and, if given, pbrt-v4, and prints both means and their ratio.
#   perf/textures/compare.sh LANTERN [PBRT] [OUT_DIR]
set -euo pipefail
LANTERN=$(realpath "$1"); PBRT=${2:+$(realpath "$2")}; OUT=${3:-/tmp/lantern-textures}
HERE=$(cd "$(dirname "$0")" && pwd)
mkdir -p "$OUT"
# The image texture: the Cornell box, rendered small.
"$LANTERN" render "$HERE/../../scenes/cornell-box.pbrt" --spp 16 --resolution 64 48 --quiet -o "$OUT/image.png" > /dev/null
cp "$HERE/textures.pbrt" "$OUT/"
cd "$OUT"
"$LANTERN" render textures.pbrt --quiet -o textures-lantern.exr > /dev/null
"$LANTERN" render textures.pbrt --quiet -o textures-lantern.png > /dev/null
if [ -n "$PBRT" ]; then
  "$PBRT" --quiet textures.pbrt > /dev/null
  "$LANTERN" compare textures-lantern.exr textures-pbrt.exr --error-image textures-error.exr | grep -E "^(mean|mean_ref|ratio|relmse) "
else
  "$LANTERN" compare textures-lantern.exr textures-lantern.exr | grep -E "^mean "
fi
