#!/bin/sh
# Error against time, per integrator and setting: relMSE and MSE of each
# variant after each of several wall times, on the shipped scenes, against
# perf/references/<scene>.exr (made by perf/make-references.sh). The
# variants: path, path with guiding (--guide), bdpt, bdpt with guiding, vcm,
# vcm with guiding; "+adaptive" adds --adaptive to a variant (vcm+adaptive,
# path+adaptive: a budget spent where the estimate says it pays). (A target
# is compared at the time it takes, docs/adaptive-sampling.md: within a
# fixed time a target no block reaches sends every pass to the noisiest
# pixels.) Prints a Markdown table; the last column is each
# variant's relMSE over path's at the same time (below 1: it pays).
# VARIANTS="path bdpt" chooses among them (path first: the ratios are to it).
# GUIDE_DISTRIBUTION (default vmm, the default) is what +guide learns with.
# Usage: perf/error-study.sh ["10 30 100"] [scenes...]   (from the repository root)
set -eu
times=${1:-"10 30 100"}
if [ $# -gt 0 ]; then shift; fi
scenes=${*:-"cornell-box cornell-box-tiny-light door-ajar lantern lamp-street caustics pool smoke"}
variants=${VARIANTS:-"path path+guide bdpt bdpt+guide vcm vcm+guide"}
lantern=${LANTERN:-build/lantern}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
echo "| scene | variant | time (s) | spp | relMSE | MSE | relMSE / path's |"
echo "|---|---|---|---|---|---|---|"
for s in $scenes; do
  ref="perf/references/$s.exr"
  [ -f "$ref" ] || { echo "perf/error-study.sh: no $ref (perf/make-references.sh makes it)" >&2; continue; }
  res="240 180"; case "$s" in cornell-box*) res="256 256" ;; lamp-street) res="240 135" ;; esac
  for t in $times; do
    path_err=""
    for v in $variants; do
      integrator=${v%%+*}
      flags=""; case "$v" in *+guide) flags="--guide --guide-distribution ${GUIDE_DISTRIBUTION:-vmm}" ;; *+adaptive) flags="--adaptive" ;; esac
      # shellcheck disable=SC2086 # flags holds zero to three words
      "$lantern" render "scenes/$s.pbrt" --integrator "$integrator" $flags --time "$t" --seed 7 --resolution $res \
        -o "$tmp/$s-$v.exr" 2> "$tmp/log" || { echo "| $s | $v | $t | (failed: $(tail -n 1 "$tmp/log")) | | | |"; continue; }
      spp=$(grep ' spp (min)' "$tmp/log" | tail -n 1 | sed -n 's/.*, \([0-9]*\) spp (min).*/\1/p')
      out=$("$lantern" compare "$tmp/$s-$v.exr" "$ref")
      err=$(echo "$out" | sed -n 's/^relmse //p')
      mse=$(echo "$out" | sed -n 's/^mse //p')
      ratio=""
      if [ "$v" = path ]; then path_err=$err; elif [ -n "$path_err" ]; then ratio=$(awk "BEGIN { printf \"%.3g\", $err / $path_err }"); fi
      echo "| $s | $v | $t | $spp | $err | $mse | $ratio |"
    done
  done
done
