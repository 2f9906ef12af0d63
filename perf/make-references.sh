#!/bin/sh
# Renders the reference images the equal-time benchmarks compare against:
# bdpt (vcm for the pools, whose caustics bdpt cannot converge, from the
# scene's merging radius) for a fixed time at a modest resolution, stored
# as half-float EXR.
# Usage: perf/make-references.sh [seconds per scene] [scenes...]   (from the repository root)
set -eu
secs=${1:-150}
if [ $# -gt 0 ]; then shift; fi
scenes=${*:-"cornell-box cornell-box-tiny-light lantern door-ajar caustics lamp-street volumetric-caustic pool pool-water spotlit-room"}
lantern=${LANTERN:-build/lantern}
# Checked before the renders, which take minutes each.
command -v oiiotool > /dev/null || { echo "perf/make-references.sh: needs oiiotool (Debian's openimageio-tools)" >&2; exit 2; }
mkdir -p perf/references
for s in $scenes; do
  res="240 180"; case "$s" in cornell-box*) res="256 256" ;; lamp-street) res="240 135" ;; esac
  integrator=bdpt; case "$s" in pool*) integrator=vcm ;; esac
  "$lantern" render "scenes/$s.pbrt" --integrator $integrator --time "$secs" --seed 424242 --resolution $res -q \
    -o "/tmp/ref-$s.exr"
  oiiotool "/tmp/ref-$s.exr" -d half --compression zip -o "perf/references/$s.exr"
done
