#!/bin/sh
# Guided light subpaths at equal time: bdpt (or $INTEGRATOR, vcm) unguided,
# with --guide-light, and with --guide --guide-light, for the same wall time at the
# reference's resolution, two seeds each; `lantern compare` measures
# relMSE (and its robust form, which leaves out the few pixels a firefly
# decides) and MSE against perf/references/<scene>.exr. Prints a Markdown
# table of the means over the seeds; the last column is the robust relMSE
# over the unguided one's (below 1: guiding pays). GUIDE_DISTRIBUTION
# (default vmm, the default; quadtree: the figures of docs/guiding-light.md)
# and GUIDE_STOP (default auto) pass --guide-distribution and --guide-stop.
# Usage: perf/light-guiding.sh [seconds] [scenes...]   (from the repository root)
set -eu
secs=${1:-10}
if [ $# -gt 0 ]; then shift; fi
scenes=${*:-"caustics door-ajar spotlit-room cornell-box cornell-box-tiny-light lamp-street lantern"}
# shellcheck disable=SC2034 # used by two_seeds
lantern=${LANTERN:-build/lantern}
integrator=${INTEGRATOR:-bdpt}
guide="--guide-distribution ${GUIDE_DISTRIBUTION:-vmm} --guide-stop ${GUIDE_STOP:-auto}"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
# shellcheck source=perf/two-seeds.sh
. "$(dirname "$0")/two-seeds.sh"
echo "| scene | $integrator | time (s) | spp | relMSE | robust relMSE | MSE | robust relMSE / unguided |"
echo "|---|---|---|---|---|---|---|---|"
for s in $scenes; do
  ref="perf/references/$s.exr"
  res="240 180"; case "$s" in cornell-box*) res="256 256" ;; lamp-street) res="240 135" ;; esac
  plain=""
  for g in unguided guide-light both; do
    case "$g" in unguided) flags="" ;; guide-light) flags="--guide-light $guide" ;; both) flags="--guide --guide-light $guide" ;; esac
    # shellcheck disable=SC2086 # flags holds zero to six words
    m=$(two_seeds "$s" "$secs" "$ref" --integrator "$integrator" $flags --resolution $res) ||
      { echo "| $s | $g | $secs | (failed) | | | | |"; [ -n "$plain" ] || plain=failed; continue; }
    # shellcheck disable=SC2086 # four numbers
    set -- $m
    robust=$3
    ratio=""
    if [ "$g" = unguided ]; then plain=$robust; elif [ "$plain" != failed ]; then ratio=$(awk "BEGIN { printf \"%.3g\", $robust / $plain }"); fi
    echo "| $s | $g | $secs | $1 | $(awk "BEGIN { printf \"%.3g\", $2 }") | $(awk "BEGIN { printf \"%.3g\", $robust }") | $(awk "BEGIN { printf \"%.3g\", $4 }") | $ratio |"
  done
done
