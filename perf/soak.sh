#!/usr/bin/env bash
# Soak test of "never lose a render": many short renders of the shipped
# scenes, a few at a time, each interrupted by SIGINT or SIGTERM at a
# random moment or left to finish, some with checkpoints. Every run must
# end with its image readable (or, interrupted before any wave merged, its
# checkpoint), and with the right exit status: 0 when finished, 130 when
# interrupted. Not part of CI.
#   perf/soak.sh LANTERN [RUNS (200)] [PARALLEL (3)] [OUT_DIR (/tmp/lantern-soak)]
set -uo pipefail
LANTERN=$(realpath "$1")
RUNS=${2:-200}
PARALLEL=${3:-3}
OUT=${4:-/tmp/lantern-soak}
SRC=$(cd "$(dirname "$0")/.." && pwd)
mkdir -p "$OUT"
scenes=("$SRC"/scenes/*.pbrt)
integrators=(path bdpt lt)

one() {
  local i=$1
  local scene=${scenes[$((RANDOM % ${#scenes[@]}))]}
  local integ=${integrators[$((RANDOM % 3))]}
  local img="$OUT/run$i.exr" log="$OUT/run$i.log"
  local extra=()
  ((RANDOM % 2)) && extra+=(--checkpoint 0.5 --checkpoint-file "$OUT/run$i.ckpt")
  rm -f "$img" "$OUT/run$i.ckpt"
  "$LANTERN" render "$scene" --integrator "$integ" --spp 64 --resolution 96 72 --quiet -o "$img" "${extra[@]}" \
    >"$log" 2>&1 &
  local pid=$!
  local action=$((RANDOM % 3))  # 0: let it finish; 1: SIGINT; 2: SIGTERM
  if ((action > 0)); then
    # At least 50 ms: a signal before main() has installed its handler
    # (while the dynamic loader runs) ends any program with 128 + signal.
    sleep "$(printf '0.%03d' $((50 + RANDOM % 900)))"
    kill -s "$([ $action = 1 ] && echo INT || echo TERM)" "$pid" 2>/dev/null
  fi
  wait "$pid"
  local rc=$?
  local verdict=ok
  if ((rc != 0 && rc != 130)); then
    verdict="bad exit $rc"
  elif [ ! -s "$img" ]; then
    verdict="no image"
  elif ! "$LANTERN" info "$img" >/dev/null 2>&1; then
    verdict="unreadable image"
  elif ((action == 0 && rc != 0)); then
    verdict="not interrupted, but exit $rc"
  fi
  echo "$i $(basename "$scene") $integ action=$action exit=$rc: $verdict"
  [ "$verdict" = ok ] && rm -f "$img" "$log" "$OUT/run$i.ckpt"
}
export -f one
export LANTERN OUT
export scenes_list="${scenes[*]}"

fails=0
for ((i = 0; i < RUNS; i += PARALLEL)); do
  for ((j = i; j < i + PARALLEL && j < RUNS; ++j)); do one "$j" & done
  wait
done | tee "$OUT/summary.txt"
fails=$(grep -vc ": ok$" "$OUT/summary.txt")
echo "soak: $RUNS runs, $fails not ok (details: $OUT/summary.txt and run*.log)"
[ "$fails" = 0 ]
