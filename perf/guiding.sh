#!/bin/sh
# Path guiding at equal time: the path tracer (or INTEGRATOR=bdpt, vcm)
# without --guide and with it, once per guiding distribution in MODELS
# (default "quadtree vmm": --guide-distribution; a name ending in -never,
# as vmm-never, adds --guide-stop never), for the same wall time
# at the reference's resolution; `lantern compare` measures relMSE, its
# firefly-robust form and MSE against perf/references/<scene>.exr (made
# by perf/make-references.sh). Prints a Markdown table; the last two
# columns are the guided relMSE and robust relMSE over the unguided ones
# (below 1: guiding pays). SEED (default 7) picks the renders' seed.
# Usage: perf/guiding.sh [seconds] [scenes...]   (from the repository root)
set -eu
secs=${1:-10}
if [ $# -gt 0 ]; then shift; fi
scenes=${*:-"spotlit-room cornell-box cornell-box-tiny-light door-ajar lantern lamp-street"}
lantern=${LANTERN:-build/lantern}
integrator=${INTEGRATOR:-path}
models=${MODELS:-"quadtree vmm"}
seed=${SEED:-7}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
echo "| scene | guided | time (s) | spp | relMSE | robust relMSE | MSE | relMSE / unguided | robust / unguided |"
echo "|---|---|---|---|---|---|---|---|---|"
for s in $scenes; do
  ref="perf/references/$s.exr"
  res="240 180"; case "$s" in cornell-box*) res="256 256" ;; lamp-street) res="240 135" ;; esac
  plain=""; plain_robust=""
  for g in no $models; do
    flag=""; [ "$g" != no ] && flag="--guide --guide-distribution ${g%-never}"
    case "$g" in *-never) flag="$flag --guide-stop never" ;; esac
    "$lantern" render "scenes/$s.pbrt" --integrator "$integrator" $flag --time "$secs" --seed "$seed" \
      --resolution $res -o "$tmp/$s-$g.exr" 2> "$tmp/log"
    spp=$(grep ' spp (min)' "$tmp/log" | tail -n 1 | sed -n 's/.*, \([0-9]*\) spp (min).*/\1/p')
    out=$("$lantern" compare "$tmp/$s-$g.exr" "$ref")
    err=$(echo "$out" | sed -n 's/^relmse //p')
    robust=$(echo "$out" | sed -n 's/^relmse_robust //p')
    mse=$(echo "$out" | sed -n 's/^mse //p')
    ratio=""; ratio_robust=""
    if [ "$g" = no ]; then
      plain=$err; plain_robust=$robust
    else
      ratio=$(awk "BEGIN { printf \"%.3g\", $err / $plain }")
      ratio_robust=$(awk "BEGIN { printf \"%.3g\", $robust / $plain_robust }")
    fi
    echo "| $s | $g | $secs | $spp | $err | $robust | $mse | $ratio | $ratio_robust |"
  done
done
