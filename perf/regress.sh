#!/bin/sh
# Samples per second of the working tree against a baseline commit, on a
# fixed set of scenes and integrators, so that a drift too small to see in
# one change shows up over several. Builds the baseline's `lantern` in a
# temporary folder (Release, as the README builds), then runs the two
# binaries alternately, `rounds` times each, and prints the median of each
# and their ratio (above 1: the working tree is faster). Compare only
# figures from one run of this script: timings on a shared machine drift.
#
# Usage: perf/regress.sh BASELINE_COMMIT [rounds] (from the repository
# root, with build/lantern built from the working tree; LANTERN overrides).
# BASELINE_COMMIT may also be a baseline binary already built.
set -eu
base=${1:?usage: perf/regress.sh BASELINE_COMMIT [rounds]}
rounds=${2:-5}
new=${LANTERN:-build/lantern}
case $new in */*) ;; *) new=./$new ;; esac  # a name without a slash would be looked up on PATH
[ -x "$new" ] || { echo "perf/regress.sh: $new is not built (cmake --build build)" >&2; exit 2; }
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
if [ -f "$base" ] && [ -x "$base" ]; then
  case $base in */*) old=$base ;; *) old=./$base ;; esac
else
  git rev-parse --verify --quiet "$base^{commit}" >/dev/null || { echo "perf/regress.sh: no commit '$base'" >&2; exit 2; }
  mkdir "$tmp/src"
  git archive "$base" | tar -x -C "$tmp/src"
  echo "building $base in $tmp ..." >&2
  cmake -S "$tmp/src" -B "$tmp/build" -G Ninja -DCMAKE_BUILD_TYPE=Release >/dev/null
  cmake --build "$tmp/build" --target lantern >/dev/null
  old="$tmp/build/lantern"
fi

# scene | integrator | extra options. The Cornell box at the settings the
# first release was measured with (independent sampler, power light
# sampler); a glass-and-water scene for vcm; fog for the media stages.
cases="cornell-box|path|--resolution 256 256 --spp 32 --sampler independent --light-sampler power
cornell-box|bdpt|--resolution 256 256 --spp 32 --sampler independent --light-sampler power
cornell-box|path|--resolution 256 256 --spp 32
lantern|bdpt|--resolution 240 180 --spp 8
pool|vcm|--resolution 240 180 --spp 16
smoke|path|--resolution 240 180 --spp 8
smoke|bdpt|--resolution 240 180 --spp 4"

# The options of a case that the baseline knows: a baseline older than an option
# (--sampler, --light-sampler) runs without it, at its own default, and
# the table says so.
"$old" render --help >"$tmp/old-help" 2>&1 || true
known() {
  out=""
  set -- $1
  while [ $# -gt 0 ]; do
    flag=$1
    shift
    vals=""
    while [ $# -gt 0 ] && [ "${1#--}" = "$1" ]; do vals="$vals $1"; shift; done
    if grep -q -- "$flag" "$tmp/old-help"; then out="$out $flag$vals"; else echo "$flag" >>"$tmp/dropped"; fi
  done
  echo "$out"
}

# Msamples/s of one render: its summary line says it (warnings may follow).
rate() {
  if ! "$1" render "scenes/$2.pbrt" --integrator "$3" --threads 2 --seed 1 $4 -o "$tmp/out.exr" 2>"$tmp/log" \
    >/dev/null </dev/null; then
    echo "perf/regress.sh: $1 failed on scenes/$2.pbrt ($3 $4):" >&2
    tail -n 3 "$tmp/log" >&2
    exit 1
  fi
  v=$(grep 'Msamples/s' "$tmp/log" | tail -n 1 | sed -n 's/.* \([0-9.]*\) Msamples\/s.*/\1/p')
  [ -n "$v" ] || { echo "perf/regress.sh: no Msamples/s in the log of $1 on scenes/$2.pbrt" >&2; exit 1; }
  echo "$v"
}
median() { sort -n | awk '{ v[NR] = $1 } END { print (NR % 2) ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2 }'; }

echo "| scene | integrator | options | $base Msamples/s | working tree | ratio |"
echo "|---|---|---|---|---|---|"
echo "$cases" | while IFS='|' read -r scene integrator opts; do
  : >"$tmp/old" && : >"$tmp/new" && : >"$tmp/dropped"
  old_opts=$(known "$opts")
  r=0
  while [ "$r" -lt "$rounds" ]; do
    rate "$old" "$scene" "$integrator" "$old_opts" >>"$tmp/old"
    rate "$new" "$scene" "$integrator" "$opts" >>"$tmp/new"
    r=$((r + 1))
  done
  a=$(median <"$tmp/old")
  b=$(median <"$tmp/new")
  note=""
  [ -s "$tmp/dropped" ] && note=" (baseline without $(sort -u "$tmp/dropped" | tr '\n' ' ' | sed 's/ $//'))"
  echo "| $scene | $integrator | $opts$note | $a | $b | $(awk "BEGIN { printf \"%.3f\", $b / $a }") |"
done
