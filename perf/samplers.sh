#!/bin/sh
# Equal-time error of each sampler: every shipped scene rendered with its
# own integrator for the same wall time with each sampler, relMSE against
# perf/references/<scene>.exr (perf/make-references.sh). Prints a Markdown
# table with each sampler's relMSE as a ratio to independent sampling's.
# Usage: perf/samplers.sh [seconds] [scenes...]   (from the repository root)
set -eu
secs=${1:-8}
if [ $# -gt 0 ]; then shift; fi
scenes=${*:-"cornell-box cornell-box-tiny-light lantern door-ajar caustics lamp-street"}
lantern=${LANTERN:-build/lantern}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
samplers="independent stratified halton sobol paddedsobol zsobol"
echo "| scene | integrator | sampler | time (s) | Msamples/s | relMSE | relMSE / independent's |"
echo "|---|---|---|---|---|---|---|"
for s in $scenes; do
  ref="perf/references/$s.exr"
  res="240 180"
  case "$s" in cornell-box*) res="256 256" ;; lamp-street) res="240 135" ;; esac
  base=""
  for k in $samplers; do
    "$lantern" render "scenes/$s.pbrt" --sampler "$k" --time "$secs" --seed 7 --resolution $res \
      -o "$tmp/$s-$k.exr" --stats "$tmp/stats.json" 2> "$tmp/log"
    integrator=$(sed -n 's/.*"integrator": "\([a-z]*\)".*/\1/p' "$tmp/stats.json" | head -n 1)
    sps=$(python3 -c "import json; print('%.3f' % (json.load(open('$tmp/stats.json'))['samples_per_second'] * 1e-6))")
    err=$("$lantern" compare "$tmp/$s-$k.exr" "$ref" | sed -n 's/^relmse //p')
    [ -n "$base" ] || base=$err
    echo "| $s | $integrator | $k | $secs | $sps | $err | $(awk "BEGIN { printf \"%.2f\", $err / $base }") |"
  done
done
