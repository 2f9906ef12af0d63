#!/bin/sh
# The cost of rendering across MPI ranks on one machine: one process with
# T threads, against T ranks of one thread, against one rank of T threads,
# same scene and settings, alternating, ROUNDS times. Prints the render
# seconds of each (the summary line's) and checks every image against the
# single-process one (they must be bit-identical: mse 0).
# (mpirun binds a rank to one core unless told --bind-to none: a rank of
# several threads needs it, or --map-by ...:PE=T on a cluster.)
# Usage: perf/mpi-overhead.sh LANTERN SCENE [ROUNDS] [THREADS] [extra render arguments...]
set -eu
lantern=$1 scene=$2 rounds=${3:-3} threads=${4:-2}
shift 2; [ $# -gt 0 ] && shift; [ $# -gt 0 ] && shift
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
out=$(mktemp -d)
seconds() { sed -n 's/.* \([0-9.]*\) s render.*/\1/p'; }
for r in $(seq "$rounds"); do
  s1=$("$lantern" render "$scene" --threads "$threads" -o "$out/single.exr" "$@" 2>&1 | seconds)
  s2=$(mpirun --oversubscribe -np "$threads" "$lantern" render "$scene" --threads 1 -o "$out/ranks.exr" "$@" 2>&1 | seconds)
  s3=$(mpirun --bind-to none -np 1 "$lantern" render "$scene" --threads "$threads" -o "$out/rank.exr" "$@" 2>&1 | seconds)
  same2=$("$lantern" compare "$out/ranks.exr" "$out/single.exr" | head -1)
  same3=$("$lantern" compare "$out/rank.exr" "$out/single.exr" | head -1)
  echo "round $r: 1 process x $threads threads ${s1} s; $threads ranks x 1 thread ${s2} s ($same2); 1 rank x $threads threads ${s3} s ($same3)"
done
rm -rf "$out"
