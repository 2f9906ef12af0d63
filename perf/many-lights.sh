#!/bin/sh
# Equal-time error on the many-light scene (scenes/lamp-street.pbrt): light
# selection by power against the light BVH, with independent samples and
# with zsobol, for path and bdpt; relMSE against
# perf/references/lamp-street.exr. Prints a Markdown table.
# Usage: perf/many-lights.sh [seconds]   (from the repository root)
set -eu
secs=${1:-20}
lantern=${LANTERN:-build/lantern}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
ref=perf/references/lamp-street.exr
echo "| integrator | light sampler | sampler | time (s) | Msamples/s | next-event samples unoccluded and non-zero | relMSE | relMSE / (power, independent)'s |"
echo "|---|---|---|---|---|---|---|---|"
for i in path bdpt; do
  base=""
  for combo in "power independent" "power zsobol" "bvh independent" "bvh zsobol"; do
    set -- $combo
    "$lantern" render scenes/lamp-street.pbrt --integrator "$i" --light-sampler "$1" --sampler "$2" \
      --time "$secs" --seed 7 --resolution 240 135 -o "$tmp/r.exr" --stats "$tmp/stats.json" 2> "$tmp/log"
    sps=$(python3 -c "import json; print('%.3f' % (json.load(open('$tmp/stats.json'))['samples_per_second'] * 1e-6))")
    frac=$(python3 -c "import json; print('%.3f' % json.load(open('$tmp/stats.json'))['next_event']['fraction'])")
    err=$("$lantern" compare "$tmp/r.exr" "$ref" | sed -n 's/^relmse //p')
    [ -n "$base" ] || base=$err
    echo "| $i | $1 | $2 | $secs | $sps | $frac | $err | $(awk "BEGIN { printf \"%.2f\", $err / $base }") |"
  done
done
