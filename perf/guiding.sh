#!/bin/sh
# Path guiding at equal time: the path tracer with and without --guide for
# the same wall time at the reference's resolution; `lantern compare`
# measures relMSE and MSE against perf/references/<scene>.exr (made by
# perf/make-references.sh). Prints a Markdown table; the last column is
# the guided relMSE over the unguided one (below 1: guiding pays).
# Usage: perf/guiding.sh [seconds] [scenes...]   (from the repository root)
set -eu
secs=${1:-10}
if [ $# -gt 0 ]; then shift; fi
scenes=${*:-"spotlit-room cornell-box cornell-box-tiny-light door-ajar lantern lamp-street"}
lantern=${LANTERN:-build/lantern}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
echo "| scene | guided | time (s) | spp | relMSE | MSE | guided relMSE / path's |"
echo "|---|---|---|---|---|---|---|"
for s in $scenes; do
  ref="perf/references/$s.exr"
  res="240 180"; case "$s" in cornell-box*) res="256 256" ;; lamp-street) res="240 135" ;; esac
  plain=""
  for g in no yes; do
    flag=""; [ "$g" = yes ] && flag="--guide"
    "$lantern" render "scenes/$s.pbrt" --integrator path $flag --time "$secs" --seed 7 --resolution $res \
      -o "$tmp/$s-$g.exr" 2> "$tmp/log"
    spp=$(grep ' spp (min)' "$tmp/log" | tail -n 1 | sed -n 's/.*, \([0-9]*\) spp (min).*/\1/p')
    out=$("$lantern" compare "$tmp/$s-$g.exr" "$ref")
    err=$(echo "$out" | sed -n 's/^relmse //p')
    mse=$(echo "$out" | sed -n 's/^mse //p')
    ratio=""
    if [ "$g" = no ]; then plain=$err; else ratio=$(awk "BEGIN { printf \"%.3g\", $err / $plain }"); fi
    echo "| $s | $g | $secs | $spp | $err | $mse | $ratio |"
  done
done
