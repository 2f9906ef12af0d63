#!/bin/sh
# Equal-time error of path, bdpt and vcm on the shipped scenes: each
# integrator renders for the same wall time at the reference's resolution,
# and `lantern compare` measures relMSE against perf/references/<scene>.exr
# (made by perf/make-references.sh). Prints a Markdown table; the last
# column is each integrator's relMSE over bdpt's; bpm runs on the pools.
# INTEGRATORS="bdpt mlt" chooses others (bdpt first: the ratios are to it).
# Usage: perf/equal-time.sh [seconds] [scenes...]   (from the repository root)
set -eu
secs=${1:-20}
if [ $# -gt 0 ]; then shift; fi
scenes=${*:-"cornell-box lantern door-ajar"}
lantern=${LANTERN:-build/lantern}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
echo "| scene | integrator | time (s) | Msamples/s | Mrays/s | relMSE | relMSE / bdpt's |"
echo "|---|---|---|---|---|---|---|"
for s in $scenes; do
  ref="perf/references/$s.exr"
  res="240 180"; case "$s" in cornell-box*) res="256 256" ;; lamp-street) res="240 135" ;; esac
  integrators=${INTEGRATORS:-"bdpt path vcm"}
  case "$s" in pool*) integrators=${INTEGRATORS:-"bdpt path vcm bpm"} ;; esac
  bdpt_err=""
  for i in $integrators; do
    "$lantern" render "scenes/$s.pbrt" --integrator "$i" --time "$secs" --seed 7 --resolution $res \
      -o "$tmp/$s-$i.exr" 2> "$tmp/log"
    summary=$(grep ' spp (min)' "$tmp/log" | tail -n 1)  # (a pilot's message may follow it)
    sps=$(echo "$summary" | sed -n 's/.* \([0-9.]*\) Msamples\/s.*/\1/p')
    rps=$(echo "$summary" | sed -n 's/.* \([0-9.]*\) Mrays\/s.*/\1/p')
    err=$("$lantern" compare "$tmp/$s-$i.exr" "$ref" | sed -n 's/^relmse //p')
    ratio=""
    if [ "$i" = bdpt ]; then bdpt_err=$err; else ratio=$(awk "BEGIN { printf \"%.3g\", $err / $bdpt_err }"); fi
    echo "| $s | $i | $secs | $sps | $rps | $err | $ratio |"
  done
done
