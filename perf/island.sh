#!/usr/bin/env bash
# The production-island-shaped scene (lantern-scenegen --island) at one or
# more scales: written once per scale, then rendered with path and bdpt at
# 1920x804, 1 spp, once per instance layout. Prints peak RSS, load time
# (of which BVH), Embree's memory, the time to the first image (--stats'
# seconds.first_image: loading and the first pass), the command's wall
# time and samples/s as a Markdown table.
#   perf/island.sh [BUILD_DIR] [WORK_DIR] [SCALES...]   (default scales: 0.01 0.03 0.1)
set -euo pipefail
build="${1:-build}"
work="${2:-/tmp/lantern-island}"
shift $(( $# > 2 ? 2 : $# ))
scales=("${@:-0.01 0.03 0.1}")
gen="$build/perf/lantern-scenegen"
lantern="$(cd "$(dirname "$build/lantern")" && pwd)/lantern"
echo "| scale | patches + triangles | curve segments | instances | layout | integrator | load s | of which BVH s | Embree MB | Embree peak MB | peak RSS MB | first image s | wall s (1 spp) | Msamples/s |"
echo "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|"
for scale in ${scales[*]}; do
  rm -rf "$work" && "$gen" "$work" --island "$scale" >/dev/null
  for layout in fast compact; do
    for integrator in path bdpt; do
      start=$(date +%s.%N)
      (cd "$work" && "$lantern" render scene.pbrt --integrator "$integrator" --spp 1 --quiet --memory-layout "$layout" \
        --stats s.json -o out.exr)
      wall=$(echo "$(date +%s.%N) - $start" | bc)
      python3 - "$work/s.json" "$scale" "$layout" "$integrator" "$wall" <<'PY'
import json, sys
j = json.load(open(sys.argv[1]))
c, s, m = j["scene_contents"], j["seconds"], j["memory"]
print(f"| {sys.argv[2]} | {c['bilinear_patches']:,} + {c['triangles']:,} tri | {c['curve_segments']:,} | {c['instances']:,} | {sys.argv[3]} | {sys.argv[4]} | "
      f"{s['load']:.1f} | {s['bvh_build']:.1f} | {m['bvh_bytes'] / 2**20:.0f} | {m['bvh_peak_bytes'] / 2**20:.0f} | "
      f"{m['peak_rss_bytes'] / 2**20:.0f} | {s.get('first_image', float('nan')):.1f} | {float(sys.argv[5]):.1f} | {j['samples_per_second'] * 1e-6:.3f} |")
PY
    done
  done
done
rm -rf "$work"
