#!/bin/sh
# The production-island scene at a small size (lantern-scenegen --island):
# the fast and the compact memory layouts render the same image (the same
# samples: only the rounding of the instances' transforms differs, so the
# images agree far below noise; a wrong transform or a lost instance moves
# them by orders of magnitude), the compact one bit-identically with 1 and
# 2 threads; and the compact layout's peak memory stays within its stated
# bounds: 400 bytes per instance and 200 per unique quad, measured as the
# growth of peak RSS against the same scene without the instances or the
# quads (docs/performance.md, "Production scale": about 225 and 105 here;
# the fast layout takes about 510 per instance, so it fails the bound).
# A verbose load names the included files as parsing reaches them. The
# generated scene Imports its placement and curve files (parsed on other
# threads, docs/scene-format.md): the image is the one of the same scene
# Including them, bit for bit. Where the kernel gives transparent huge
# pages on request, the heap is in them (--stats), and not with
# LANTERN_HUGE_PAGES=0.
#   sh tests/island_test.sh LANTERN SCENEGEN
set -eu
lantern=$1 gen=$2
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
fail() { echo "island test: $*" >&2; exit 1; }
"$gen" "$tmp/isl" --island 0.005 --prototypes 64 >/dev/null
cd "$tmp/isl"
render() {  # SCENE OUT LAYOUT THREADS [more options]
  scene=$1 out=$2 layout=$3 threads=$4
  shift 4
  "$lantern" render "$scene" -q --spp 4 --resolution 192 80 --memory-layout "$layout" --threads "$threads" \
    --stats "$out.json" -o "$out.exr" "$@"
}
field() { python3 -c "import json, sys; j = json.load(open(sys.argv[1])); print(eval(sys.argv[2]))" "$1" "$2"; }

render scene.pbrt fast fast 2
render scene.pbrt compact compact 2
render scene.pbrt compact1 compact 1
[ "$(field compact.json "j['memory']['compact_instances']")" = True ] || fail "compact layout without compact instances"
[ "$(field fast.json "j['memory']['compact_instances']")" = False ] || fail "fast layout with compact instances"
[ "$(field fast.json "j['seconds']['first_image'] >= j['seconds']['load'] > 0")" = True ] ||
  fail "--stats has no time to the first image"
relmse=$("$lantern" compare compact.exr fast.exr | sed -n 's/^relmse //p')
python3 -c "import sys; sys.exit(0 if float('$relmse') < 1e-4 else 1)" ||
  fail "compact and fast layouts differ: relMSE $relmse"
"$lantern" render scene.pbrt --log-level verbose --spp 1 --resolution 16 8 -o verbose.exr 2>verbose.log
grep -q 'parsing: 1 included files, .* MB; curves/grass_00000.pbrt' verbose.log ||
  fail "a verbose load does not report the included files it parses: $(head -5 verbose.log)"
[ "$("$lantern" compare compact.exr compact1.exr | sed -n 's/^mse //p')" = 0 ] ||
  fail "compact layout: 1 and 2 threads differ"
grep -q '^Import "instances/' scene.pbrt || fail "the generated scene does not Import its placements"
sed 's/^Import /Include /' scene.pbrt >included.pbrt
render included.pbrt included compact 2
[ "$("$lantern" compare compact.exr included.exr | sed -n 's/^mse //p')" = 0 ] ||
  fail "Import'ed and Include'd files give different images"

policy=$(cat /sys/kernel/mm/transparent_hugepage/enabled 2>/dev/null || echo none)
case "$policy" in *"[madvise]"* | *"[always]"*) want=True ;; *) want=False ;; esac
[ "$(field compact.json "j['memory']['huge_pages']")" = $want ] || fail "huge pages: not $want under policy '$policy'"
LANTERN_HUGE_PAGES=0 render scene.pbrt small compact 2
case "$policy" in *"[madvise]"*)
  [ "$(field small.json "j['memory']['huge_pages']")" = False ] || fail "huge pages with LANTERN_HUGE_PAGES=0"
  [ "$(field compact.json "j['memory']['anon_huge_pages_bytes']")" -gt "$(field small.json "j['memory']['anon_huge_pages_bytes']")" ] ||
    fail "no more memory in huge pages with them than without" ;;
esac

# Peak memory: the same scene without its instances, and without its quads.
grep -v 'instances/' scene.pbrt >noinst.pbrt
grep -v 'meshes/terrain\|meshes/panels' scene.pbrt >noquads.pbrt
render noinst.pbrt noinst compact 2
render noquads.pbrt noquads compact 2
python3 - <<'PY' || fail "peak memory above its bounds"
import json
s, ni, nq = (json.load(open(f + ".json")) for f in ("compact", "noinst", "noquads"))
peak = lambda j: j["memory"]["peak_rss_bytes"]
c = s["scene_contents"]
quads = c["bilinear_patches"] + (c["triangles"] - nq["scene_contents"]["triangles"]) / 2
per_instance = (peak(s) - peak(ni)) / c["instances"]
per_quad = (peak(s) - peak(nq)) / quads
print(f"island: {c['instances']} instances, {quads:.0f} quads: {per_instance:.0f} bytes per instance, {per_quad:.0f} per quad")
assert per_instance <= 400, per_instance
assert per_quad <= 200, per_quad
PY
