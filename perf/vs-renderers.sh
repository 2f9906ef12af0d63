#!/bin/sh
# Error at equal time against other renderers: Lantern (path, bdpt), pbrt-v4
# (path, bdpt) and Blender's Cycles (CPU; path tracing with its adaptive
# sampling, and with its path guiding where the build has it) on shipped
# scenes, each renderer's relMSE and MSE against its own converged image of
# the same scene, so that no renderer is charged for another's small
# differences of model. Prints a Markdown table.
#
#   perf/vs-renderers.sh ["10 30"] [scenes...]      (from the repository root)
#
# PBRT: a pbrt-v4 binary (its rows are left out without one); BLENDER:
# Blender's binary (default `blender`, Debian's package; left out if
# absent); REFTIME: seconds for each of their converged images (default
# 600), kept in $CACHE (default ~/.cache/lantern-vs-renderers) by scene,
# resolution and renderer. Lantern's references are perf/references/.
#
# PAIRS=1 renders Lantern's and Cycles' timed images twice, seeds 7 and 8,
# and adds each one's variance measured without a reference: half the MSE
# and relMSE between the two images (the second image stands in for the
# reference in relMSE's denominator). A converged image's own noise adds
# to the error against it (the Cornell box's reference in
# perf/references/ once added more than a 30 s render's variance); the
# pair has none, and an unbiased renderer's error is its variance.
#
# pbrt-v4 has no time budget: it renders a number of samples per pixel
# chosen from a short timing run to take about the budget, and its error
# is scaled to the budget by the time it took (error falls as 1/time for
# an unbiased estimator): the "time" column says what it took.
# Cycles' time limit covers its render alone, as Lantern's --time does.
set -eu
times=${1:-"10 30"}
if [ $# -gt 0 ]; then shift; fi
scenes=${*:-"cornell-box cornell-box-tiny-light door-ajar lamp-street"}
lantern=${LANTERN:-build/lantern}
blender=${BLENDER:-blender}
reftime=${REFTIME:-600}
cache=${CACHE:-$HOME/.cache/lantern-vs-renderers}
mkdir -p "$cache"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
here=$(cd "$(dirname "$0")" && pwd)
have_blender=no
command -v "$blender" > /dev/null 2>&1 && have_blender=yes

# The scene with its Film resolution and Integrator replaced (pbrt-v4 has no
# flags for them): scene_for SCENE W H INTEGRATOR OUT
scene_for() {
  python3 - "$1" "$2" "$3" "$4" "$5" <<'EOF'
import re, sys
src, w, h, integrator, out = sys.argv[1:]
t = open(src).read()
t = re.sub(r'("integer xresolution"\s*)\[?\s*\d+\s*\]?', r'\g<1>[ %s ]' % w, t)
t = re.sub(r'("integer yresolution"\s*)\[?\s*\d+\s*\]?', r'\g<1>[ %s ]' % h, t)
t = re.sub(r'Integrator\s+"\w+"', 'Integrator "%s"' % integrator, t)
if integrator != "path":  # pbrt-v4's bdpt has no light sampler to choose
    t = re.sub(r'"string lightsampler"\s*\[?\s*"\w+"\s*\]?', '', t)
open(out, 'w').write(t)
EOF
}

# pbrt-v4's render time: the last "(N.Ns)" of its progress line.
pbrt_seconds() { tr '\r' '\n' < "$1" | sed -n 's/.*(\([0-9.]*\)s).*/\1/p' | tail -n 1; }

# pbrt_render SCENE_FILE SPP OUT LOG [SEED]: the converged images take seed 1,
# the timed ones 7 (with one seed their first samples would be the same).
pbrt_render() { (cd "$(dirname "$1")" && "$PBRT" --seed "${5:-7}" --spp "$2" "$(basename "$1")" --outfile "$3") > "$4" 2>&1; }

# pbrt_spp_for SCENE_FILE SECONDS: samples per pixel for about SECONDS.
pbrt_spp_for() {
  pbrt_render "$1" 8 "$tmp/probe.exr" "$tmp/probe.log"
  awk -v s="$(pbrt_seconds "$tmp/probe.log")" -v t="$2" 'BEGIN { n = int(8 * t / (s > 0.01 ? s : 0.01)); print (n < 1 ? 1 : n) }'
}

pairs=${PAIRS:-}
row() {
  if [ -n "$pairs" ]; then echo "| $1 | $2 | $3 | $4 | $5 | $6 | ${7:-} | ${8:-} |"
  else echo "| $1 | $2 | $3 | $4 | $5 | $6 |"; fi
}
errors() { "$lantern" compare "$1" "$2" | sed -n 's/^\(relmse\|mse\) //p' | tr '\n' ' '; }
# pair_errors A B: half the relMSE and MSE between two seeds' images.
pair_errors() {
  "$lantern" compare "$1" "$2" | sed -n 's/^\(relmse\|mse\) //p' | awk '{ printf "%.3g ", $1 / 2 }'
}

if [ -n "$pairs" ]; then
  echo "| scene | renderer | time (s) | spp | relMSE | MSE | relMSE, seeds 7 and 8 | MSE, seeds 7 and 8 |"
  echo "|---|---|---|---|---|---|---|---|"
else
  echo "| scene | renderer | time (s) | spp | relMSE | MSE |"
  echo "|---|---|---|---|---|---|"
fi
for s in $scenes; do
  res="240 180"; case "$s" in cornell-box*) res="256 256" ;; lamp-street) res="240 135" ;; esac
  w=${res% *}; h=${res#* }
  ref="perf/references/$s.exr"
  for t in $times; do
    for i in path bdpt; do
      "$lantern" render "scenes/$s.pbrt" --integrator $i --time "$t" --seed 7 --resolution $res -o "$tmp/l.exr" \
        2> "$tmp/log"
      spp=$(sed -n 's/.*, \([0-9]*\) spp (min).*/\1/p' "$tmp/log" | tail -n 1)  # (bdpt's rate line may follow)
      pair=""
      if [ -n "$pairs" ]; then
        "$lantern" render "scenes/$s.pbrt" --integrator $i --time "$t" --seed 8 --resolution $res -q -o "$tmp/l8.exr"
        pair=$(pair_errors "$tmp/l.exr" "$tmp/l8.exr")
      fi
      set -- $(errors "$tmp/l.exr" "$ref") $pair
      row "$s" "Lantern $i" "$t" "$spp" "$2" "$1" "${4:-}" "${3:-}"
    done
    if [ -n "${PBRT:-}" ]; then
      for i in path bdpt; do
        scene_for "scenes/$s.pbrt" "$w" "$h" "$i" "$tmp/$s-$i.pbrt"
        pref="$cache/pbrt-$s-$w-$h-$i.exr"
        if [ ! -f "$pref" ]; then
          pbrt_render "$tmp/$s-$i.pbrt" "$(pbrt_spp_for "$tmp/$s-$i.pbrt" "$reftime")" "$pref" "$tmp/plog" 1
        fi
        n=$(pbrt_spp_for "$tmp/$s-$i.pbrt" "$t")
        pbrt_render "$tmp/$s-$i.pbrt" "$n" "$tmp/p.exr" "$tmp/plog"
        took=$(pbrt_seconds "$tmp/plog")
        set -- $(errors "$tmp/p.exr" "$pref")
        row "$s" "pbrt-v4 $i" "$took" "$n" "$(awk -v e="$2" -v a="$took" -v t="$t" 'BEGIN { printf "%.3g", e * a / t }')" \
          "$(awk -v e="$1" -v a="$took" -v t="$t" 'BEGIN { printf "%.3g", e * a / t }')"
      done
    fi
    if [ $have_blender = yes ]; then
      cref="$cache/cycles-$s-$w-$h.exr"
      if [ ! -f "$cref" ]; then
        "$blender" -b --factory-startup -P "$here/cycles/scene_to_cycles.py" -- "scenes/$s.pbrt" "$cref" --time "$reftime" \
          --no-adaptive --seed 1 --resolution $w $h > "$tmp/clog" 2>&1 || { tail -n 5 "$tmp/clog" >&2; exit 1; }
      fi
      variants=cycles
      "$blender" -b --factory-startup --python-expr \
        'import sys, _cycles; sys.exit(0 if getattr(_cycles, "with_path_guiding", False) else 1)' \
        > /dev/null 2>&1 && variants="cycles cycles+guiding"
      for v in $variants; do
        flags=""; [ $v = cycles+guiding ] && flags="--guiding"
        # shellcheck disable=SC2086 # flags holds zero or one word
        if "$blender" -b --factory-startup -P "$here/cycles/scene_to_cycles.py" -- "scenes/$s.pbrt" "$tmp/c.exr" --time "$t" \
          --seed 7 --resolution $w $h $flags > "$tmp/clog" 2>&1; then
          pair=""
          if [ -n "$pairs" ] && "$blender" -b --factory-startup -P "$here/cycles/scene_to_cycles.py" -- "scenes/$s.pbrt" \
            "$tmp/c8.exr" --time "$t" --seed 8 --resolution $w $h $flags > "$tmp/clog" 2>&1; then
            pair=$(pair_errors "$tmp/c.exr" "$tmp/c8.exr")
          fi
          set -- $(errors "$tmp/c.exr" "$cref") $pair
          row "$s" "$([ $v = cycles ] && echo Cycles || echo "Cycles, guided")" "$t" "" "$2" "$1" "${4:-}" "${3:-}"
        else
          row "$s" "$v" "$t" "(failed: $(tail -n 1 "$tmp/clog"))" "" ""
        fi
      done
    fi
  done
done
