#!/usr/bin/env bash
# Load time, BVH build time, peak memory and samples/s against scene size,
# on lantern-scenegen's forest: instanced triangles at fixed unique ones,
# then unique triangles at fixed instanced ones. bdpt, 960x540, 2 spp.
#   perf/large-scenes.sh [BUILD_DIR] [WORK_DIR]
# Prints a Markdown table; the generated scenes go to WORK_DIR (default
# /tmp/lantern-large) and are deleted after each run.
set -euo pipefail
build="${1:-build}"
work="${2:-/tmp/lantern-large}"
gen="$build/perf/lantern-scenegen"
lantern="$build/lantern"
echo "| instanced triangles | unique triangles | instances | load s | of which BVH s | BVH MB | geometry MB | peak RSS MB | render Msamples/s |"
echo "|---|---|---|---|---|---|---|---|---|"
run() {
  rm -rf "$work" && "$gen" "$work" --instanced-triangles "$1" --unique-triangles "$2" >/dev/null
  "$lantern" render "$work/scene.pbrt" --spp 2 --resolution 960 540 --quiet --stats "$work/s.json" -o "$work/out.exr"
  python3 - "$work/s.json" <<'PY'
import json, sys
j = json.load(open(sys.argv[1]))
c, s, m = j["scene_contents"], j["seconds"], j["memory"]
print(f"| {c['instanced_triangles']:,} | {c['triangles']:,} | {c['instances']:,} | {s['load']:.2f} | {s['bvh_build']:.2f} | "
      f"{m['bvh_bytes'] / 2**20:.0f} | {m['geometry_bytes'] / 2**20:.0f} | {m['peak_rss_bytes'] / 2**20:.0f} | "
      f"{j['samples_per_second'] * 1e-6:.3f} |")
PY
  rm -rf "$work"
}
for n in 1e6 1e7 1e8 1e9; do run "$n" 1e6; done
for u in 5e6 1e7 2e7; do run 1e6 "$u"; done
