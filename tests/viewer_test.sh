#!/bin/sh
# `lantern view` in a real window under Xvfb, driven by keys as a user
# would (xdotool): it renders the scene pass by pass; F1's screenshot equals
# `lantern render` of the same settings bit for bit; R reloads an edited
# file (the light doubled: the image doubles); W moves the camera (the image
# changes); Escape closes the window with exit 0.
#   sh tests/viewer_test.sh LANTERN SOURCE_DIR WORK_DIR
set -eu
lantern=$1 src=$2 work=$3/viewer
if [ -z "${VIEWER_TEST_INNER:-}" ]; then
  for tool in xvfb-run xdotool; do
    command -v $tool >/dev/null || { echo "viewer test: $tool is not installed (scripts/install-deps.sh)" >&2; exit 1; }
  done
  rm -rf "$work" && mkdir -p "$work"
  VIEWER_TEST_INNER=1 exec xvfb-run -a -s "-screen 0 640x480x24" sh "$0" "$@"
fi

log=$work/log
fail() { echo "viewer test: $*" >&2; echo "--- viewer output:" >&2; cat "$log" >&2; kill "$pid" 2>/dev/null || true; exit 1; }
# Waits until the viewer's output holds `count` lines matching `pattern`.
wait_for() {
  pattern=$1 count=$2 tries=0
  while n=$(grep -c -- "$pattern" "$log" 2>/dev/null || true); [ "${n:-0}" -lt "$count" ]; do
    tries=$((tries + 1))
    [ $tries -le 600 ] || fail "no '$pattern' (x$count) within 60 s"
    kill -0 "$pid" 2>/dev/null || fail "the viewer exited early"
    sleep 0.1
  done
}
# A key pressed with the window focused (XTEST, as a keyboard would).
press() {
  window=$(timeout 30 xdotool search --sync --name '^lantern' | head -n 1)
  [ -n "$window" ] || fail "no window named lantern"
  xdotool windowfocus --sync "$window"
  xdotool key "$1"
}

cp "$src/scenes/cornell-box.pbrt" "$work/scene.pbrt"
settings="--resolution 48 40 --spp 32 --seed 3 --integrator bdpt"
# (The log exists before the viewer starts: the background job opens it
# when it runs, and wait_for must not read a missing file as done.)
: >"$log"
"$lantern" view "$work/scene.pbrt" $settings --screenshot "$work/shot" >"$log" 2>&1 &
pid=$!
wait_for "^view: done 32 spp" 1
# Passes of 16 samples: the window showed the render at 16 spp, then 32.
[ "$(grep -c '^view: pass ' "$log")" -ge 2 ] || fail "fewer than two passes shown"
press F1
wait_for "^view: screenshot .*shot-1.exr" 1
"$lantern" render "$work/scene.pbrt" $settings -q -o "$work/reference.exr" || fail "lantern render failed"
"$lantern" compare "$work/shot-1.exr" "$work/reference.exr" >"$work/compare1" || fail "compare failed"
grep -q '^mse 0$' "$work/compare1" || fail "the screenshot is not the render's image: $(cat "$work/compare1")"

# The light doubled in the file; R reloads it, keeping the camera.
sed -i 's/"rgb L" \[ 17 12 4 \]/"rgb L" [ 34 24 8 ]/' "$work/scene.pbrt"
grep -q '34 24 8' "$work/scene.pbrt" || fail "could not edit the scene"
press r
wait_for "^view: reloaded" 1
wait_for "^view: done 32 spp" 2
press F1
wait_for "^view: screenshot .*shot-2.exr" 1
"$lantern" compare "$work/shot-2.exr" "$work/reference.exr" >"$work/compare2" || fail "compare failed"
awk '/^ratio/ { seen = 1; for (i = 2; i <= 4; ++i) if ($i < 1.999 || $i > 2.001) exit 1 } END { exit !seen }' \
  "$work/compare2" ||
  fail "the reloaded scene's image is not twice the first: $(cat "$work/compare2")"

# W steps the camera forward: a new render of another view.
press w
wait_for "^view: started" 3
wait_for "^view: done 32 spp" 3
press F1
wait_for "^view: screenshot .*shot-3.exr" 1
"$lantern" compare "$work/shot-3.exr" "$work/shot-2.exr" >"$work/compare3" || fail "compare failed"
if grep -q '^mse 0$' "$work/compare3"; then fail "W did not move the camera"; fi

press Escape
wait "$pid" || fail "the viewer exited with status $?"
grep -q "^view: closed" "$log" || fail "no 'closed'"
echo "viewer test: passed"
