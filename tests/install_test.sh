#!/bin/sh
# `cmake --install` into a temporary prefix, then the prefix moved: the
# installed command and Python module work from where they are, loading the
# installed image module (not the build's); the man page documents every
# option `lantern render --help` lists; the completion script parses.
#   sh tests/install_test.sh BUILD_DIR SOURCE_DIR [PYTHON]
set -eu
build=$1 src=$2 python=${3:-}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
fail() { echo "install test: $*" >&2; exit 1; }
cmake --install "$build" --prefix "$tmp/prefix" >/dev/null
mv "$tmp/prefix" "$tmp/moved"
p=$tmp/moved
for f in bin/lantern lib/lantern/liblantern_imageio.so share/man/man1/lantern.1 share/bash-completion/completions/lantern; do
  [ -e "$p/$f" ] || fail "$f was not installed"
done

# The installed command renders a PNG (written through the image module),
# and the module it loads is the installed one.
LD_DEBUG=files "$p/bin/lantern" render "$src/scenes/cornell-box.pbrt" --spp 1 --resolution 16 16 -q -o "$tmp/x.png" \
  2>"$tmp/ld.log" || fail "the installed lantern failed: $(grep -v '^ *[0-9]*:' "$tmp/ld.log")"
[ -s "$tmp/x.png" ] || fail "no image"
loaded=$(grep -o 'file=[^ ]*liblantern_imageio.so' "$tmp/ld.log" | head -n 1 | sed 's/^file=//')
case "$loaded" in "$p"/*) ;; *) fail "the installed lantern loaded the image module from '$loaded', not from $p" ;; esac

# Run by its bare name from PATH, in a folder that holds a folder named
# lantern (where argv[0] would point if taken for a path): still found.
mkdir -p "$tmp/work/lantern"
(cd "$tmp/work" && PATH="$p/bin:$PATH" lantern render "$src/scenes/cornell-box.pbrt" --spp 1 --resolution 8 8 -q \
  -o "$tmp/work/y.png") || fail "lantern run from PATH could not write a PNG"

# Every long option of `render --help` is in the man page.
man_text=$(sed 's/\\//g' "$p/share/man/man1/lantern.1")
options=$("$p/bin/lantern" render --help | grep -o -- '--[a-z][a-z0-9-]*' | sort -u)
[ -n "$options" ] || fail "lantern render --help listed no options"
for opt in $options; do
  printf '%s' "$man_text" | grep -q -- "$opt" || fail "the man page does not mention $opt"
done
bash -n "$p/share/bash-completion/completions/lantern" || fail "the completion script does not parse"

# The Python module from the moved prefix, with its own copy of the image module.
if [ -n "$python" ]; then
  [ -e "$p/lib/python3/dist-packages/lantern/__init__.py" ] || fail "the Python package was not installed"
  PYTHONPATH="$p/lib/python3/dist-packages" LD_DEBUG=files "$python" -c "
import lantern, numpy
s = lantern.load_scene('$src/scenes/cornell-box.pbrt')
r = lantern.render(s, spp=1, resolution=(8, 8))
lantern.write_image('$tmp/y.exr', r.image)
assert lantern.__file__.startswith('$p'), lantern.__file__
" 2>"$tmp/py.log" || fail "the installed Python module failed: $(grep -v '^ *[0-9]*:' "$tmp/py.log")"
  loaded=$(grep -o 'file=[^ ]*liblantern_imageio.so' "$tmp/py.log" | head -n 1 | sed 's/^file=//')
  case "$loaded" in "$p"/*) ;; *) fail "the installed Python module loaded the image module from '$loaded'" ;; esac
fi
echo "install test: passed ($p)"
