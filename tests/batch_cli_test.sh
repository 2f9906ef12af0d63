#!/bin/sh
# What a batch job uses of the command line, end to end: render regions
# (--cropwindow, --pixelbounds, --pixel) as the Film's own crops make them,
# partial images written while the render runs, log levels and a log file,
# the image on standard output, the note on a changed aspect ratio, and the
# exit codes of each misuse.
#   sh tests/batch_cli_test.sh LANTERN SOURCE_DIR
set -eu
lantern=$1 src=$2
tmp=$(cd "$(mktemp -d)" && pwd -P)  # (canonical: the module loader prints canonical paths)
pid=
trap '[ -n "$pid" ] && kill "$pid" 2>/dev/null; rm -rf "$tmp"' EXIT
fail() { echo "batch cli test: $*" >&2; exit 1; }
box=$src/scenes/cornell-box.pbrt
small="--spp 1 --resolution 40 30"
# mse of two images, as lantern compare prints it.
mse() { "$lantern" compare "$1" "$2" | sed -n 's/^mse //p'; }
expect_code() {  # CODE DESCRIPTION COMMAND...
  want=$1 what=$2
  shift 2
  set +e
  "$@" >"$tmp/out" 2>"$tmp/err"
  got=$?
  set -e
  [ "$got" = "$want" ] || fail "$what: exit $got, expected $want ($(cat "$tmp/err"))"
}

# --- Render regions: the command line's region renders the pixels the
# Film's "cropwindow" / "pixelbounds" render, bit for bit.
sed 's|^Film "rgb"|Film "rgb" "float cropwindow" [0.25 0.75 0.5 1]|' "$box" >"$tmp/crop.pbrt"
sed 's|^Film "rgb"|Film "rgb" "integer pixelbounds" [10 20 5 15]|' "$box" >"$tmp/bounds.pbrt"
sed 's|^Film "rgb"|Film "rgb" "integer pixelbounds" [23 24 20 21]|' "$box" >"$tmp/pixel.pbrt"
grep -q cropwindow "$tmp/crop.pbrt" || fail "the test scene has no Film line to crop"
"$lantern" render "$tmp/crop.pbrt" $small -q -o "$tmp/film_crop.exr"
"$lantern" render "$box" $small -q --cropwindow 0.25,0.75,0.5,1 -o "$tmp/cli_crop.exr"
[ "$(mse "$tmp/cli_crop.exr" "$tmp/film_crop.exr")" = 0 ] || fail "--cropwindow differs from the Film's cropwindow"
"$lantern" render "$tmp/bounds.pbrt" $small -q -o "$tmp/film_bounds.exr"
"$lantern" render "$box" $small -q --pixelbounds 10 20 5 15 -o "$tmp/cli_bounds.exr"
[ "$(mse "$tmp/cli_bounds.exr" "$tmp/film_bounds.exr")" = 0 ] || fail "--pixelbounds differs from the Film's pixelbounds"
"$lantern" info "$tmp/cli_bounds.exr" | grep -q '^resolution 10 10$' || fail "--pixelbounds 10 20 5 15 is not 10x10"
"$lantern" render "$tmp/pixel.pbrt" $small -q -o "$tmp/film_pixel.exr"
"$lantern" render "$box" $small --pixel 23,20 -o "$tmp/cli_pixel.exr" 2>"$tmp/err"
[ "$(mse "$tmp/cli_pixel.exr" "$tmp/film_pixel.exr")" = 0 ] || fail "--pixel differs from the Film's one-pixel bounds"
grep -q '^pixel value: ' "$tmp/err" || fail "--pixel did not print the pixel's value"
# A region over the Film's own: the command line's wins (pbrt-v4's rule).
"$lantern" render "$tmp/crop.pbrt" $small -q --pixelbounds 10 20 5 15 -o "$tmp/over.exr"
[ "$(mse "$tmp/over.exr" "$tmp/film_bounds.exr")" = 0 ] || fail "--pixelbounds did not replace the Film's cropwindow"
expect_code 2 "--cropwindow out of order" "$lantern" render "$box" $small --cropwindow 0.5,0.2,0,1 -o "$tmp/x.exr"
expect_code 2 "--cropwindow with --pixel" "$lantern" render "$box" $small --cropwindow 0,1,0,1 --pixel 1,1 -o "$tmp/x.exr"
expect_code 2 "--pixel outside the image" "$lantern" render "$box" $small --pixel 40,3 -o "$tmp/x.exr"
grep -q 'covers no pixel of the 40x30 image' "$tmp/err" || fail "--pixel outside the image: $(cat "$tmp/err")"

# --- The aspect ratio changed by --resolution is explained.
"$lantern" render "$box" --spp 1 --resolution 64 32 -o "$tmp/wide.exr" 2>"$tmp/err"
grep -q 'aspect ratio 2 where the scene.s Film (512x512) has 1' "$tmp/err" || fail "no note on the changed aspect ratio"

# --- A parameter neither pbrt-v4 nor pbrt-v3 reads (a typo) stops the load
# with its file and line, as pbrt-v4 does; --lenient renders with a warning.
sed 's|^Sampler "\([a-z]*\)"|Sampler "\1" "integer pixelsampels" [1]|' "$box" >"$tmp/typo.pbrt"
expect_code 2 "an unknown parameter" "$lantern" render "$tmp/typo.pbrt" $small -o "$tmp/x.exr"
grep -q 'typo.pbrt:10:[0-9]*: error: Sampler "zsobol": unknown parameter "integer pixelsampels".*did you mean "pixelsamples"' "$tmp/err" ||
  fail "an unknown parameter: $(cat "$tmp/err")"
"$lantern" render "$tmp/typo.pbrt" $small --lenient -q -o "$tmp/x.exr" 2>"$tmp/err" || fail "--lenient did not render"
grep -q 'typo.pbrt:10:[0-9]*: warning: .*pixelsampels' "$tmp/err" || fail "--lenient gave no warning: $(cat "$tmp/err")"

# --- Log levels and a log file. A scene with a warning (a parameter pbrt
# knows and Lantern does not use) shows it at warning and info, not at
# error; the summary only from info; the settings and passes only at
# verbose.
sed 's|^Sampler "\([a-z]*\)"|Sampler "\1" "integer dimensions" [1]|' "$box" >"$tmp/warn.pbrt"
grep -q dimensions "$tmp/warn.pbrt" || fail "the test scene has no Sampler line"
for level in error warning info verbose; do
  "$lantern" render "$tmp/warn.pbrt" $small --log-level $level -o "$tmp/l.exr" 2>"$tmp/$level.log"
done
[ ! -s "$tmp/error.log" ] || fail "--log-level error printed: $(cat "$tmp/error.log")"
grep -q dimensions "$tmp/warning.log" || fail "--log-level warning hid the warning"
! grep -q 'spp (min)' "$tmp/warning.log" || fail "--log-level warning printed the summary"
grep -q 'spp (min)' "$tmp/info.log" || fail "--log-level info has no summary"
! grep -q '^render: ' "$tmp/info.log" || fail "--log-level info printed the verbose settings"
grep -q '^render: path, 1 spp' "$tmp/verbose.log" || fail "--log-level verbose has no settings line"
grep -q '^pass: 1 spp' "$tmp/verbose.log" || fail "--log-level verbose has no pass line"
"$lantern" render "$tmp/warn.pbrt" $small -q -o "$tmp/l.exr" 2>"$tmp/quiet.log"
grep -q dimensions "$tmp/quiet.log" && ! grep -q 'spp (min)' "$tmp/quiet.log" || fail "-q is not --log-level warning"
echo "an earlier line" >"$tmp/job.log"
"$lantern" render "$tmp/warn.pbrt" $small --log-file "$tmp/job.log" -o "$tmp/l.exr" 2>"$tmp/err"
[ ! -s "$tmp/err" ] || fail "--log-file left messages on stderr: $(cat "$tmp/err")"
[ "$(head -n 1 "$tmp/job.log")" = "an earlier line" ] || fail "--log-file did not append"
grep -q dimensions "$tmp/job.log" && grep -q 'spp (min)' "$tmp/job.log" || fail "--log-file lacks the messages"
expect_code 2 "an unknown log level" "$lantern" render "$box" $small --log-level loud -o "$tmp/x.exr"

# --- The image on standard output: the bytes of the file render.
"$lantern" render "$box" $small -q -o - >"$tmp/stdout.exr"
"$lantern" render "$box" $small -q -o "$tmp/file.exr"
[ "$(mse "$tmp/stdout.exr" "$tmp/file.exr")" = 0 ] || fail "-o - is not the image -o FILE writes"
expect_code 2 "two outputs on standard output" "$lantern" render "$box" $small -o - --stats -
# A reader that goes away: exit 1 and a rescue copy, never a silent loss.
set +e
(cd "$tmp" && "$lantern" render "$box" --spp 1 --resolution 256 256 -q -o - 2>"$tmp/err" | head -c 10 >/dev/null)
set -e
grep -q 'saved instead in .*stdout.rescue.exr' "$tmp/err" || fail "a closed pipe lost the image: $(cat "$tmp/err")"
# The error map on standard output moves the metrics to stderr.
"$lantern" compare "$tmp/file.exr" "$tmp/file.exr" --error-image - >"$tmp/map.exr" 2>"$tmp/err"
grep -q '^mse 0$' "$tmp/err" || fail "compare --error-image - did not print the metrics on stderr"
"$lantern" info "$tmp/map.exr" | grep -q 'lantern:error_map' || fail "compare --error-image - wrote no map"

# --- Partial images: while a timed render runs, its output holds the image
# so far (lantern:partial true, fewer samples); interrupted, the final image
# replaces it.
"$lantern" render "$box" --time 60 --resolution 40 30 -q --write-partial-images=0.2 -o "$tmp/partial.exr" 2>/dev/null &
pid=$!
tries=0
until [ -s "$tmp/partial.exr" ] && "$lantern" info "$tmp/partial.exr" 2>/dev/null | grep -q '^lantern:partial true'; do
  tries=$((tries + 1))
  [ $tries -lt 600 ] || fail "no partial image after 60 s"
  kill -0 $pid 2>/dev/null || fail "the render ended before writing a partial image"
  sleep 0.1
done
partial_samples=$("$lantern" info "$tmp/partial.exr" | sed -n 's/^lantern:samples //p')
[ "$partial_samples" -gt 0 ] || fail "a partial image without samples"
kill -INT $pid
set +e
wait $pid
code=$?
set -e
pid=
[ $code = 130 ] || fail "the interrupted render exited $code, expected 130"
"$lantern" info "$tmp/partial.exr" >"$tmp/info"
! grep -q '^lantern:partial' "$tmp/info" || fail "the final image is marked partial"
grep -q '^lantern:interrupted true' "$tmp/info" || fail "the final image is not the interrupted render's"
final_samples=$(sed -n 's/^lantern:samples //p' "$tmp/info")
[ "$final_samples" -ge "$partial_samples" ] || fail "the final image has fewer samples than a partial one"
expect_code 2 "--write-partial-images with -o -" "$lantern" render "$box" $small --write-partial-images -o -
expect_code 2 "--write-partial-images with --part" "$lantern" render "$box" $small --write-partial-images --part 1/2 \
  -o "$tmp/p.film"
# --- A binary moved away from its image module: a clear error, each place
# it looked in named once (in the main program the executable's folder
# used to be named twice).
mkdir "$tmp/alone"
cp "$lantern" "$tmp/alone/lantern"
expect_code 1 "a render without the image module" env -u LANTERN_IMAGEIO_MODULE "$tmp/alone/lantern" render "$box" $small \
  -o "$tmp/alone.exr"
grep -q "cannot load Lantern's image module" "$tmp/err" || fail "no clear error without the image module: $(cat "$tmp/err")"
grep -q "$tmp/alone/liblantern_imageio.so: not found" "$tmp/err" || fail "the error does not name the binary's folder"
[ -z "$(grep ': not found$' "$tmp/err" | sort | uniq -d)" ] || fail "the error names a place twice: $(cat "$tmp/err")"
echo "batch cli test: passed"
