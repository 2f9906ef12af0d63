#!/bin/sh
# The path tracer's Russian roulette at equal time: `--roulette S` for each
# S (1 is pbrt-v4's rule), the same wall time at the reference's
# resolution, two seeds each; `lantern compare` measures relMSE (and its
# robust form, which leaves out the few pixels a firefly decides) and MSE
# against perf/references/<scene>.exr. Prints a Markdown table of the means
# over the seeds; the last two columns are relMSE and MSE over S = 1's
# (below 1: the scale pays).
# Usage: perf/roulette.sh [seconds] [scenes...]   (from the repository root;
# SCALES="1 2 4" chooses the scales, the first being the baseline)
set -eu
secs=${1:-10}
if [ $# -gt 0 ]; then shift; fi
scenes=${*:-"cornell-box cornell-box-tiny-light door-ajar lamp-street lantern spotlit-room caustics pool pool-water volumetric-caustic"}
scales=${SCALES:-"1 2 4"}
# shellcheck disable=SC2034 # used by two_seeds
lantern=${LANTERN:-build/lantern}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
# shellcheck source=perf/two-seeds.sh
. "$(dirname "$0")/two-seeds.sh"
echo "| scene | roulette | time (s) | spp | relMSE | robust relMSE | MSE | relMSE / baseline | MSE / baseline |"
echo "|---|---|---|---|---|---|---|---|---|"
for s in $scenes; do
  ref="perf/references/$s.exr"
  [ -f "$ref" ] || { echo "perf/roulette.sh: no $ref (perf/make-references.sh makes it)" >&2; continue; }
  res="240 180"; case "$s" in cornell-box*) res="256 256" ;; lamp-street) res="240 135" ;; esac
  new_baseline
  for k in $scales; do
    # shellcheck disable=SC2086 # res is two words
    m=$(two_seeds "$s" "$secs" "$ref" --integrator path --roulette "$k" --resolution $res) || m=""
    row "$s | $k" "$secs" "$m"
  done
done
