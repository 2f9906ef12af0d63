#!/bin/sh
# bdpt's light subpath rate at equal time: `--light-subpaths Q` for each Q
# (1 is pbrt-v4's bdpt, auto the pilot's choice), the same wall time at the
# reference's resolution, two seeds each; `lantern compare` measures
# relMSE (and its robust form) and MSE against perf/references/<scene>.exr.
# Prints a Markdown table of the means over the seeds; the last two
# columns are relMSE and MSE over the first rate's (below 1: it pays), and
# the path tracer's row is there to hold bdpt against.
# Usage: perf/light-subpaths.sh [seconds] [scenes...]   (from the repository
# root; RATES="1 auto 0.5 0.25" chooses the rates, the first the baseline)
set -eu
secs=${1:-10}
if [ $# -gt 0 ]; then shift; fi
scenes=${*:-"cornell-box cornell-box-tiny-light door-ajar lamp-street lantern spotlit-room caustics pool pool-water volumetric-caustic"}
rates=${RATES:-"1 auto 0.5 0.25"}
# shellcheck disable=SC2034 # used by two_seeds
lantern=${LANTERN:-build/lantern}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
# shellcheck source=perf/two-seeds.sh
. "$(dirname "$0")/two-seeds.sh"
echo "| scene | integrator | light subpaths | time (s) | spp | relMSE | robust relMSE | MSE | relMSE / baseline | MSE / baseline |"
echo "|---|---|---|---|---|---|---|---|---|---|"
for s in $scenes; do
  ref="perf/references/$s.exr"
  [ -f "$ref" ] || { echo "perf/light-subpaths.sh: no $ref (perf/make-references.sh makes it)" >&2; continue; }
  res="240 180"; case "$s" in cornell-box*) res="256 256" ;; lamp-street) res="240 135" ;; esac
  new_baseline
  for k in $rates; do
    # shellcheck disable=SC2086 # res is two words
    m=$(two_seeds "$s" "$secs" "$ref" --integrator bdpt --light-subpaths "$k" --resolution $res) || m=""
    row "$s | bdpt | $k" "$secs" "$m"
  done
  # shellcheck disable=SC2086 # res is two words
  m=$(two_seeds "$s" "$secs" "$ref" --integrator path --resolution $res) || m=""
  row "$s | path | -" "$secs" "$m"
done
