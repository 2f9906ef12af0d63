#!/usr/bin/env bash
# Renders perf/textures/textures.pbrt (every texture class and mapping),
# cutouts.pbrt (alpha, mix, interface), bumps.pbrt (bump and normal maps) and
# filtering.pbrt (textures filtered over the pixel footprint) with Lantern
# and, if given, pbrt-v4, and prints both means and their ratio.
#   [SCENES="filtering ..."] perf/textures/compare.sh LANTERN [PBRT] [OUT_DIR]
set -euo pipefail
LANTERN=$(realpath "$1"); PBRT=${2:+$(realpath "$2")}; OUT=${3:-/tmp/lantern-textures}
HERE=$(cd "$(dirname "$0")" && pwd)
mkdir -p "$OUT"
# The image texture: the Cornell box, rendered small.
"$LANTERN" render "$HERE/../../scenes/cornell-box.pbrt" --spp 16 --resolution 64 48 --quiet -o "$OUT/image.png" > /dev/null
python3 "$HERE/make-normal-map.py" "$OUT/normals.pfm"
python3 "$HERE/make-fine-image.py" "$OUT/fine.pfm"
cp "$HERE/textures.pbrt" "$HERE/cutouts.pbrt" "$HERE/bumps.pbrt" "$HERE/filtering.pbrt" "$OUT/"
cd "$OUT"
for scene in ${SCENES:-textures cutouts bumps filtering}; do
  echo "== $scene"
  "$LANTERN" render $scene.pbrt --quiet -o $scene-lantern.exr > /dev/null
  "$LANTERN" render $scene.pbrt --quiet -o $scene-lantern.png > /dev/null
  if [ -n "$PBRT" ]; then
    "$PBRT" --quiet $scene.pbrt > /dev/null 2>&1
    "$LANTERN" compare $scene-lantern.exr $scene-pbrt.exr --error-image $scene-error.exr | grep -E "^(mean|mean_ref|ratio|relmse) "
  else
    "$LANTERN" compare $scene-lantern.exr $scene-lantern.exr | grep -E "^mean "
  fi
done
