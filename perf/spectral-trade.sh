#!/bin/sh
# Samples per second of --spectral against RGB: every shipped scene (or the
# scenes named), path and bdpt, same binary, rendered in turn (RGB, spectral,
# RGB, ...) so that the machine's drift falls on both alike. Prints a
# Markdown table of the median spectral samples/s over the median RGB's.
# Usage: perf/spectral-trade.sh [rounds] [scenes...]   (from the repository root)
set -eu
rounds=${1:-3}
if [ $# -gt 0 ]; then shift; fi
scenes=${*:-$(ls scenes/*.pbrt | sed 's|scenes/||; s|\.pbrt$||')}
lantern=${LANTERN:-build/lantern}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

# samples/s of one render, from its --stats file
rate() {
  "$lantern" render "scenes/$1.pbrt" --integrator "$2" --resolution 160 120 --spp 8 \
    $3 -o "$tmp/out.exr" --stats "$tmp/stats.json" 2> "$tmp/log" ||
    { echo "render failed: $1 $2 $3" >&2; cat "$tmp/log" >&2; exit 1; }
  python3 -c "import json; print(json.load(open('$tmp/stats.json'))['samples_per_second'])"
}

median() {
  tr ' ' '\n' | sed '/^$/d' | sort -g | awk '{ v[NR] = $1 } END { print v[int((NR + 1) / 2)] }'
}

echo "| scene | path | bdpt |"
echo "|---|---|---|"
for s in $scenes; do
  row="| $s |"
  for i in path bdpt; do
    rgb="" spectral=""
    r=0
    while [ "$r" -lt "$rounds" ]; do
      rgb="$rgb $(rate "$s" "$i" "")"
      spectral="$spectral $(rate "$s" "$i" --spectral)"
      r=$((r + 1))
    done
    a=$(echo "$rgb" | median)
    b=$(echo "$spectral" | median)
    row="$row $(awk "BEGIN { printf \"%.2f\", $b / $a }") |"
  done
  echo "$row"
done
