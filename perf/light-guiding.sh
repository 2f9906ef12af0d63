#!/bin/sh
# Guided light subpaths at equal time: bdpt (or $INTEGRATOR, vcm) unguided,
# with --guide-light, and with --guide --guide-light, for the same wall time at the
# reference's resolution, two seeds each; `lantern compare` measures
# relMSE (and its robust form, which leaves out the few pixels a firefly
# decides) and MSE against perf/references/<scene>.exr. Prints a Markdown
# table of the means over the seeds; the last column is the robust relMSE
# over the unguided one's (below 1: guiding pays).
# Usage: perf/light-guiding.sh [seconds] [scenes...]   (from the repository root)
set -eu
secs=${1:-10}
shift 2>/dev/null || true
scenes=${*:-"caustics door-ajar spotlit-room cornell-box cornell-box-tiny-light lamp-street lantern"}
lantern=${LANTERN:-build/lantern}
integrator=${INTEGRATOR:-bdpt}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
echo "| scene | $integrator | time (s) | spp | relMSE | robust relMSE | MSE | robust relMSE / unguided |"
echo "|---|---|---|---|---|---|---|---|"
for s in $scenes; do
  ref="perf/references/$s.exr"
  res="240 180"; case "$s" in cornell-box*) res="256 256" ;; lamp-street) res="240 135" ;; esac
  plain=""
  for g in unguided guide-light both; do
    case "$g" in unguided) flags="" ;; guide-light) flags="--guide-light" ;; both) flags="--guide --guide-light" ;; esac
    sum="0 0 0 0"
    for seed in 7 8; do
      "$lantern" render "scenes/$s.pbrt" --integrator "$integrator" $flags --time "$secs" --seed $seed --resolution $res \
        -o "$tmp/$s.exr" 2> "$tmp/log"
      spp=$(tail -n 1 "$tmp/log" | sed -n 's/.*, \([0-9]*\) spp (min).*/\1/p')
      out=$("$lantern" compare "$tmp/$s.exr" "$ref")
      sum=$(echo "$sum $spp $(echo "$out" | sed -n 's/^relmse //p') $(echo "$out" | sed -n 's/^relmse_robust //p') \
        $(echo "$out" | sed -n 's/^mse //p')" | awk '{ printf "%g %g %g %g", $1 + $5, $2 + $6, $3 + $7, $4 + $8 }')
    done
    set -- $sum
    robust=$(awk "BEGIN { print $3 / 2 }")
    ratio=""
    if [ "$g" = unguided ]; then plain=$robust; else ratio=$(awk "BEGIN { printf \"%.3g\", $robust / $plain }"); fi
    echo "| $s | $g | $secs | $(awk "BEGIN { print int($1 / 2) }") | $(awk "BEGIN { printf \"%.3g\", $2 / 2 }") | $(awk "BEGIN { printf \"%.3g\", $robust }") | $(awk "BEGIN { printf \"%.3g\", $4 / 2 }") | $ratio |"
  done
done
