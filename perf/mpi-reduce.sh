#!/bin/sh
# The cost of adding the ranks' films at rank 0 against image size: two
# ranks render the Cornell box at 1 spp (path: no splat buffer; bdpt: with
# one) at 512x512 to 8K, and --stats reports each rank's reduction time and
# bytes. Usage: perf/mpi-reduce.sh LANTERN [RANKS]
set -eu
lantern=$1 ranks=${2:-2}
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_btl=self,vader
out=$(mktemp -d)
for integrator in path bdpt; do
  for res in "512 512" "1024 1024" "2048 2048" "3840 2160" "7680 4320"; do
    mpirun --oversubscribe --bind-to none -np "$ranks" "$lantern" render scenes/cornell-box.pbrt --integrator $integrator \
      --spp 1 --threads 1 --resolution $res -q -o "$out/r.exr" --stats "$out/r.json"
    python3 - "$out/r.json" "$integrator" "$res" <<'PY'
import json, sys
d = json.load(open(sys.argv[1]))["mpi"]["per_rank"][0]
mb = d["communication_bytes"] / 2**20
print(f'{sys.argv[2]:5} {sys.argv[3]:>10}: {mb:8.1f} MB per rank, reduction {d["communication_seconds"]:.3f} s at rank 0 '
      f'({mb / max(d["communication_seconds"], 1e-9):.0f} MB/s)')
PY
  done
done
rm -rf "$out"
