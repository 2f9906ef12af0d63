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
shift 2>/dev/null || true
scenes=${*:-"cornell-box cornell-box-tiny-light door-ajar lamp-street lantern spotlit-room caustics pool pool-water volumetric-caustic"}
scales=${SCALES:-"1 2 4"}
lantern=${LANTERN:-build/lantern}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
echo "| scene | roulette | time (s) | spp | relMSE | robust relMSE | MSE | relMSE / baseline | MSE / baseline |"
echo "|---|---|---|---|---|---|---|---|---|"
for s in $scenes; do
  ref="perf/references/$s.exr"
  [ -f "$ref" ] || { echo "perf/roulette.sh: no $ref (perf/make-references.sh makes it)" >&2; continue; }
  res="240 180"; case "$s" in cornell-box*) res="256 256" ;; lamp-street) res="240 135" ;; esac
  base_rel=""; base_mse=""
  for k in $scales; do
    sum="0 0 0 0"
    for seed in 7 8; do
      "$lantern" render "scenes/$s.pbrt" --integrator path --roulette "$k" --time "$secs" --seed $seed --resolution $res \
        -o "$tmp/$s.exr" 2> "$tmp/log"
      spp=$(tail -n 1 "$tmp/log" | sed -n 's/.*, \([0-9]*\) spp (min).*/\1/p')
      out=$("$lantern" compare "$tmp/$s.exr" "$ref")
      sum=$(echo "$sum $spp $(echo "$out" | sed -n 's/^relmse //p') $(echo "$out" | sed -n 's/^relmse_robust //p') \
        $(echo "$out" | sed -n 's/^mse //p')" | awk '{ printf "%g %g %g %g", $1 + $5, $2 + $6, $3 + $7, $4 + $8 }')
    done
    set -- $sum
    rel=$(awk "BEGIN { print $2 / 2 }"); mse=$(awk "BEGIN { print $4 / 2 }")
    r1=""; r2=""
    if [ -z "$base_rel" ]; then base_rel=$rel; base_mse=$mse
    else r1=$(awk "BEGIN { printf \"%.3g\", $rel / $base_rel }"); r2=$(awk "BEGIN { printf \"%.3g\", $mse / $base_mse }"); fi
    echo "| $s | $k | $secs | $(awk "BEGIN { print int($1 / 2) }") | $(awk "BEGIN { printf \"%.3g\", $rel }") | $(awk "BEGIN { printf \"%.3g\", $3 / 2 }") | $(awk "BEGIN { printf \"%.3g\", $mse }") | $r1 | $r2 |"
  done
done
