#!/bin/sh
# Error at equal time against other renderers: Lantern, pbrt-v4 and
# Blender's Cycles (CPU; path tracing with its adaptive
# sampling, without it, and with its path guiding where the build has it:
# its adaptive sampling, aiming at a low noise threshold to use the whole
# budget, can leave more error than uniform sampling) on shipped
# scenes, each renderer's relMSE and MSE against its own converged image of
# the same scene, so that no renderer is charged for another's small
# differences of model. Prints a Markdown table (perf/vs-summary.py reduces
# it to Lantern's best against each peer's best).
#
#   perf/vs-renderers.sh ["10 30"] [scenes...]      (from the repository root)
#
# PBRT: a pbrt-v4 binary (its rows are left out without one); BLENDER:
# Blender's binary (default `blender`, Debian's package; left out if
# absent); REFTIME: seconds for each of their converged images (default
# 600), kept in $CACHE (default ~/.cache/lantern-vs-renderers) by scene,
# resolution and renderer. Lantern's references are perf/references/.
#
# Each renderer runs its path tracer and bdpt, and also the scene's own
# integrator where it is another (sppm: Lantern's vcm and pbrt-v4's sppm);
# pbrt-v4's path tracer is its volpath where the scene has media, and its
# sppm, which ignores media, is not run there (a row says so). LANTERN_EXTRA
# adds Lantern runs, each an integrator with options joined by commas
# (LANTERN_EXTRA="path,--guide bdpt,--guide").
#
# PAIRS=1 renders every timed image twice, seeds 7 and 8, and adds each
# one's variance measured without a reference: half the MSE and relMSE
# between the two images (their mean stands in for the reference in
# relMSE's denominator). A converged image's own noise adds to the error
# against it (the Cornell box's reference in perf/references/ once added
# more than a 30 s render's variance); the pair has none, and an unbiased
# renderer's error is its variance (a consistent one's, vcm's and sppm's,
# is its variance and its bias, which the pair does not see). With PAIRS=1
# a scene without a Lantern reference is measured by its pairs alone, for
# every renderer (no converged images are made for it).
#
# The last column, robust relMSE, is relMSE against the reference without
# the 0.01% of pixels whose error is largest (lantern compare's
# relmse_robust), the mean over the seeds rendered: where one rare bright
# sample is most of a relMSE (a light seen through a filter's tail, a
# caustic a path tracer found once), it says what the rest of the image
# looks like, for every renderer alike.
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
def integrator_line(m):
    # pbrt-v4 refuses parameters an integrator does not read: another
    # integrator keeps only maxdepth, and the path tracers the light sampler.
    own, params = m.group(1), re.findall(r'"(\w+) (\w+)"\s*(\[[^\]]*\]|"[^"]*"|[^\s"\[]+)', m.group(2))
    keep = [p for p in params if own == integrator or p[1] == "maxdepth"
            or (p[1] == "lightsampler" and integrator in ("path", "volpath"))]
    return 'Integrator "%s"' % integrator + "".join(' "%s %s" %s' % p for p in keep) + "\n"
t = re.sub(r'Integrator\s+"(\w+)"((?:\s*"\w+ \w+"\s*(?:\[[^\]]*\]|"[^"]*"|[^\s"\[]+))*)\s*', integrator_line, t)
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
  pbrt_render "$1" 8 "$tmp/probe.exr" "$tmp/probe.log" || return 1
  awk -v s="$(pbrt_seconds "$tmp/probe.log")" -v t="$2" 'BEGIN { n = int(8 * t / (s > 0.01 ? s : 0.01)); print (n < 1 ? 1 : n) }'
}

# to_budget ERROR TOOK BUDGET: an error measured after TOOK seconds, at the
# budget (empty stays empty).
to_budget() { [ -z "$1" ] || awk -v e="$1" -v a="$2" -v t="$3" 'BEGIN { printf "%.3g", e * a / t }'; }

pairs=${PAIRS:-}
if [ -n "$pairs" ] && ! command -v oiiotool > /dev/null; then
  echo "perf/vs-renderers.sh: PAIRS=1 needs oiiotool (Debian's openimageio-tools)" >&2
  exit 2
fi
row() {
  if [ -n "$pairs" ]; then echo "| $1 | $2 | $3 | $4 | $5 | $6 | ${7:-} | ${8:-} | ${9:-} |"
  else echo "| $1 | $2 | $3 | $4 | $5 | $6 | ${9:-} |"; fi
}
errors() { "$lantern" compare "$1" "$2" | sed -n 's/^\(relmse\|mse\) //p' | tr '\n' ' '; }
# robust REF IMAGE...: relMSE without the 0.01% of pixels whose error is
# largest (lantern compare's relmse_robust: one rare bright sample can be
# most of a relMSE), the mean over the images (the seeds rendered).
robust() {
  r=$1; shift
  for f; do "$lantern" compare "$f" "$r" | sed -n 's/^relmse_robust //p'; done |
    awk '{ s += $1; n++ } END { if (n) printf "%.3g", s / n }'
}
# pair_errors A B: one image's variance from two seeds' images, as relMSE
# and MSE: twice the errors of A against their mean M. (a - m)^2 is a
# quarter of (a - b)^2, whose half estimates the variance. The mean in
# relMSE's denominator, not B: a dark pixel of B under a bright one of A
# would count hundreds of times what it does against a converged image.
pair_errors() {
  oiiotool "$1" "$2" --add --mulc 0.5 -o "$tmp/mean.exr"
  "$lantern" compare "$1" "$tmp/mean.exr" | sed -n 's/^\(relmse\|mse\) //p' | awk '{ printf "%.3g ", $1 * 2 }'
}

if [ -n "$pairs" ]; then
  echo "| scene | renderer | time (s) | spp | relMSE | MSE | relMSE, seeds 7 and 8 | MSE, seeds 7 and 8 | robust relMSE |"
  echo "|---|---|---|---|---|---|---|---|---|"
else
  echo "| scene | renderer | time (s) | spp | relMSE | MSE | robust relMSE |"
  echo "|---|---|---|---|---|---|---|"
fi
for s in $scenes; do
  res="240 180"; case "$s" in cornell-box*) res="256 256" ;; lamp-street) res="240 135" ;; esac
  w=${res% *}; h=${res#* }
  ref="perf/references/$s.exr"
  if [ ! -f "$ref" ] && [ -z "$pairs" ]; then
    echo "perf/vs-renderers.sh: $ref is missing (make it with perf/make-references.sh, or measure by pairs: PAIRS=1)" >&2
    exit 2
  fi
  own=$(sed -n 's/^ *Integrator *"\([a-z]*\)".*/\1/p' "scenes/$s.pbrt" | head -n 1)
  lruns="path bdpt"; pruns="path bdpt"
  case "$own" in sppm) lruns="$lruns vcm"; pruns="$pruns sppm" ;; vcm | bpm | ppm) lruns="$lruns $own" ;; esac
  grep -q MakeNamedMedium "scenes/$s.pbrt" && pruns=$(echo "$pruns" | sed 's/path/volpath/')
  for t in $times; do
    for run in $lruns ${LANTERN_EXTRA:-}; do
      args=$(echo "$run" | tr ',' ' ')
      i=${args%% *}; opts=""; [ "$i" != "$args" ] && opts=${args#* }
      # shellcheck disable=SC2086 # opts holds the run's own options, split on purpose
      "$lantern" render "scenes/$s.pbrt" --integrator $i $opts --time "$t" --seed 7 --resolution $res -o "$tmp/l.exr" \
        2> "$tmp/log"
      spp=$(sed -n 's/.*, \([0-9]*\) spp (min).*/\1/p' "$tmp/log" | tail -n 1)  # (bdpt's rate line may follow)
      pair="" seeds="$tmp/l.exr"
      if [ -n "$pairs" ]; then
        # shellcheck disable=SC2086
        "$lantern" render "scenes/$s.pbrt" --integrator $i $opts --time "$t" --seed 8 --resolution $res -q -o "$tmp/l8.exr"
        pair=$(pair_errors "$tmp/l.exr" "$tmp/l8.exr") seeds="$seeds $tmp/l8.exr"
      fi
      rob=""
      # shellcheck disable=SC2086 # seeds holds one or two file names
      [ -f "$ref" ] && rob=$(robust "$ref" $seeds)
      if [ -f "$ref" ]; then set -- $(errors "$tmp/l.exr" "$ref") $pair; else set -- "" "" $pair; fi
      row "$s" "Lantern $args" "$t" "$spp" "$2" "$1" "${4:-}" "${3:-}" "$rob"
    done
    if [ -n "${PBRT:-}" ]; then
      for i in $pruns; do
        # pbrt-v4's sppm passes through medium boundaries and never samples
        # a medium: its image would be another scene's
        if [ "$i" = sppm ] && grep -q MakeNamedMedium "scenes/$s.pbrt"; then
          row "$s" "pbrt-v4 $i" "" "(not run: pbrt-v4's sppm ignores participating media)" "" ""
          continue
        fi
        scene_for "scenes/$s.pbrt" "$w" "$h" "$i" "$tmp/$s-$i.pbrt"
        pref="$cache/pbrt-$s-$w-$h-$i.exr"
        # a scene pbrt-v4 refuses (its bdpt takes perspective cameras only)
        # gets its message in the table
        if ! n=$(pbrt_spp_for "$tmp/$s-$i.pbrt" "$t"); then
          row "$s" "pbrt-v4 $i" "" "(failed: $(grep -a Error "$tmp/probe.log" | head -n 1 | sed 's/\x1b\[[0-9;]*m//g'))" "" ""
          continue
        fi
        if [ -f "$ref" ] && [ ! -f "$pref" ]; then
          pbrt_render "$tmp/$s-$i.pbrt" "$(pbrt_spp_for "$tmp/$s-$i.pbrt" "$reftime")" "$pref" "$tmp/plog" 1
        fi
        pbrt_render "$tmp/$s-$i.pbrt" "$n" "$tmp/p.exr" "$tmp/plog"
        took=$(pbrt_seconds "$tmp/plog")
        pair="" seeds="$tmp/p.exr"
        if [ -n "$pairs" ]; then
          pbrt_render "$tmp/$s-$i.pbrt" "$n" "$tmp/p8.exr" "$tmp/plog8" 8
          pair=$(pair_errors "$tmp/p.exr" "$tmp/p8.exr") seeds="$seeds $tmp/p8.exr"
        fi
        rob=""
        # shellcheck disable=SC2086
        [ -f "$ref" ] && rob=$(robust "$pref" $seeds)
        # scaled to the budget: error falls as 1/time
        if [ -f "$ref" ]; then set -- $(errors "$tmp/p.exr" "$pref") $pair; else set -- "" "" $pair; fi
        row "$s" "pbrt-v4 $i" "$took" "$n" "$(to_budget "$2" "$took" "$t")" "$(to_budget "$1" "$took" "$t")" \
          "$(to_budget "${4:-}" "$took" "$t")" "$(to_budget "${3:-}" "$took" "$t")" "$(to_budget "$rob" "$took" "$t")"
      done
    fi
    if [ $have_blender = yes ]; then
      cref="$cache/cycles-$s-$w-$h.exr"
      if [ -f "$ref" ] && [ ! -f "$cref" ] && ! { "$blender" -b --factory-startup -P "$here/cycles/scene_to_cycles.py" -- \
        "scenes/$s.pbrt" "$cref" --time "$reftime" --no-adaptive --seed 1 --resolution $w $h > "$tmp/clog" 2>&1 &&
        [ -f "$cref" ]; }; then
        # a scene the Blender script cannot build (it says which line)
        row "$s" Cycles "$t" "(failed: $(grep scene_to_cycles "$tmp/clog" | tail -n 1))" "" ""
        continue
      fi
      variants="cycles cycles-uniform"
      "$blender" -b --factory-startup --python-expr \
        'import sys, _cycles; sys.exit(0 if getattr(_cycles, "with_path_guiding", False) else 1)' \
        > /dev/null 2>&1 && variants="$variants cycles+guiding"
      for v in $variants; do
        case $v in cycles+guiding) flags="--guiding" name="Cycles, guided" ;;
          cycles-uniform) flags="--no-adaptive" name="Cycles, uniform" ;; *) flags="" name=Cycles ;; esac
        rm -f "$tmp/c.exr" "$tmp/c8.exr"  # (Blender's exit status alone does not say it wrote one)
        # shellcheck disable=SC2086 # flags holds zero or one word
        if "$blender" -b --factory-startup -P "$here/cycles/scene_to_cycles.py" -- "scenes/$s.pbrt" "$tmp/c.exr" --time "$t" \
          --seed 7 --resolution $w $h $flags > "$tmp/clog" 2>&1 && [ -f "$tmp/c.exr" ]; then
          pair="" seeds="$tmp/c.exr"
          if [ -n "$pairs" ] && "$blender" -b --factory-startup -P "$here/cycles/scene_to_cycles.py" -- "scenes/$s.pbrt" \
            "$tmp/c8.exr" --time "$t" --seed 8 --resolution $w $h $flags > "$tmp/clog" 2>&1 && [ -f "$tmp/c8.exr" ]; then
            pair=$(pair_errors "$tmp/c.exr" "$tmp/c8.exr") seeds="$seeds $tmp/c8.exr"
          fi
          rob=""
          # shellcheck disable=SC2086
          [ -f "$ref" ] && rob=$(robust "$cref" $seeds)
          if [ -f "$ref" ]; then set -- $(errors "$tmp/c.exr" "$cref") $pair; else set -- "" "" $pair; fi
          row "$s" "$name" "$t" "" "$2" "$1" "${4:-}" "${3:-}" "$rob"
        else
          row "$s" "$v" "$t" "(failed: $(tail -n 1 "$tmp/clog"))" "" ""
        fi
      done
    fi
  done
done
