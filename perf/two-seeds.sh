# shellcheck shell=sh disable=SC2154 # lantern and tmp are the caller's
# Sourced by perf/light-guiding.sh, perf/roulette.sh and
# perf/light-subpaths.sh: one setting of a scene rendered for the same
# wall time with seeds 7 and 8 and measured against its reference.
#   two_seeds SCENE SECONDS REFERENCE OPTIONS...
# prints the means over the two seeds: "spp relMSE robust-relMSE MSE".
# Needs $lantern (the binary) and $tmp (a scratch folder).
two_seeds() {
  _scene=$1 _secs=$2 _ref=$3
  shift 3
  _sum="0 0 0 0"
  for _seed in 7 8; do
    "$lantern" render "scenes/$_scene.pbrt" "$@" --time "$_secs" --seed $_seed -o "$tmp/$_scene.exr" 2> "$tmp/log" ||
      { echo "two_seeds: $_scene failed: $(tail -n 1 "$tmp/log")" >&2; return 1; }
    _spp=$(sed -n 's/.*, \([0-9]*\) spp (min).*/\1/p' "$tmp/log" | tail -n 1)
    _out=$("$lantern" compare "$tmp/$_scene.exr" "$_ref") || { echo "two_seeds: $_scene: compare failed" >&2; return 1; }
    _row="$_spp $(echo "$_out" | sed -n 's/^relmse //p') $(echo "$_out" | sed -n 's/^relmse_robust //p') $(echo "$_out" | sed -n 's/^mse //p')"
    [ "$(echo "$_row" | wc -w)" -eq 4 ] || { echo "two_seeds: $_scene: expected spp, relmse, relmse_robust, mse; got '$_row'" >&2; return 1; }
    _sum=$(echo "$_sum $_row" | awk '{ printf "%g %g %g %g", $1 + $5, $2 + $6, $3 + $7, $4 + $8 }')
  done
  echo "$_sum" | awk '{ printf "%d %g %g %g\n", $1 / 2, $2 / 2, $3 / 2, $4 / 2 }'
}

# Resets the baseline: the next `row` of a scene is it.
new_baseline() { _base_rel=""; _base_mse=""; }

# row LABELS SECONDS "spp relMSE robust-relMSE MSE"|"" prints a table row:
# "| LABELS | SECONDS | spp | relMSE | robust relMSE | MSE | relMSE /
# baseline | MSE / baseline |", LABELS being the row's first cells
# ("scene | setting"). Empty numbers: a failed render's row. The first row
# after new_baseline is the baseline (a failed one leaves the ratios out).
row() {
  if [ -z "$3" ]; then
    echo "| $1 | $2 | (failed) | | | | | |"
    [ -n "$_base_rel" ] || _base_rel=failed
    return
  fi
  # shellcheck disable=SC2086 # four numbers
  set -- "$1" "$2" $3
  _r1=""; _r2=""
  if [ -z "$_base_rel" ]; then _base_rel=$4; _base_mse=$6
  elif [ "$_base_rel" != failed ]; then
    _r1=$(awk "BEGIN { printf \"%.3g\", $4 / $_base_rel }"); _r2=$(awk "BEGIN { printf \"%.3g\", $6 / $_base_mse }")
  fi
  echo "| $1 | $2 | $3 | $(awk "BEGIN { printf \"%.3g\", $4 }") | $(awk "BEGIN { printf \"%.3g\", $5 }") | $(awk "BEGIN { printf \"%.3g\", $6 }") | $_r1 | $_r2 |"
}
