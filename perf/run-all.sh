#!/bin/sh
# Runs the whole benchmark set and writes its tables, CSV files and plots to
# perf/results/<UTC date>-<git revision>/, with the machine described in
# machine.txt. About 10-12 minutes on 2 cores. Build first (the README's
# commands); this builds the benchmark drivers (target perf); BUILD= names
# another build folder.
# Usage: perf/run-all.sh            (from anywhere in the repository)
set -eu
cd "$(dirname "$0")/.."
build=${BUILD:-build}
cmake --build "$build" --target perf
rev=$(git rev-parse --short HEAD 2>/dev/null || echo unknown)
[ -z "$(git status --porcelain 2>/dev/null)" ] || rev="$rev-dirty"
dir="perf/results/$(date -u +%Y%m%d-%H%M%S)-$rev"
mkdir -p "$dir"
{
  echo "date: $(date -u)"
  echo "revision: $rev"
  uname -srm
  echo "cores: $(nproc)"
  grep -m1 "model name" /proc/cpuinfo || true
  free -h | head -2
} > "$dir/machine.txt"

bench="$build/perf/lantern-bench --out $dir"
say() { echo "== $*" >&2; }

say throughput
$bench throughput --spp 16 > "$dir/throughput.md"
say "ray back ends"
$bench backends --scene cornell-box --integrator path --spp 32 > "$dir/backends-path.md"
$bench backends --scene lantern --integrator bdpt --spp 8 > "$dir/backends-bdpt.md"
say scaling
$bench scaling --scene cornell-box --integrator path --spp 16 > "$dir/scaling.md"
for s in cornell-box lantern door-ajar; do
  say "convergence $s"
  $bench convergence --scene "$s" --max-seconds 16 > "$dir/convergence-$s.md"
  if command -v gnuplot > /dev/null; then
    gnuplot -e "
      set terminal pngcairo size 640,480 noenhanced; set output '$dir/convergence-$s.png';
      set datafile separator ','; set logscale xy; set grid;
      set title 'relMSE against time: $s'; set xlabel 'render time (s)'; set ylabel 'relMSE';
      plot for [i in 'path lt bdpt'] '$dir/convergence_$s.csv' using 3:(strcol(1) eq i ? \$5 : NaN) \
           with linespoints title i" 2> /dev/null \
    || gnuplot -e "
      set terminal png size 640,480; set output '$dir/convergence-$s.png';
      set datafile separator ','; set logscale xy; set grid;
      set title 'relMSE against time: $s'; set xlabel 'render time (s)'; set ylabel 'relMSE';
      plot for [i in 'path lt bdpt'] '$dir/convergence_$s.csv' using 3:(strcol(1) eq i ? \$5 : NaN) \
           with linespoints title i"
  else
    echo "gnuplot not installed: no plot (scripts/install-deps.sh installs it)" >&2
  fi
done
say "ray replay"
tmp=$(mktemp -d)
"$build/lantern" render scenes/lantern.pbrt --integrator bdpt --spp 2 --resolution 240 180 -q -o "$tmp/r.exr" \
  --stats "$dir/raybench-render-stats.json" --dump-rays "$tmp/rays.bin"
"$build/perf/lantern-raybench" scenes/lantern.pbrt "$tmp/rays.bin" --benchmark_min_time=0.3 \
  --benchmark_out="$dir/raybench.json" --benchmark_out_format=json > "$dir/raybench.txt" 2>&1
rm -rf "$tmp"
say "equal time"
LANTERN="$build/lantern" perf/equal-time.sh 20 cornell-box cornell-box-tiny-light lantern door-ajar caustics volumetric-caustic \
  > "$dir/equal-time.md"
echo "$dir"
