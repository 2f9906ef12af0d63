#!/usr/bin/env bash
# Installs every Debian 12 package Lantern needs to build, test and benchmark.
# Idempotent: packages already present are skipped, apt is only called when
# something is missing.
set -euo pipefail

packages=(
  build-essential cmake ninja-build pkg-config
  libembree-dev libtbb-dev libopenimageio-dev libglm-dev
  libcli11-dev nlohmann-json3-dev zlib1g-dev
  libnanovdb-dev  # header only: the "nanovdb" medium (src/medium/nanovdb_grid.cpp)
  libboost-dev  # header only: Joe & Kuo's Sobol direction numbers (src/sampler/sobol_matrices.cpp)
  libgtest-dev libgmock-dev libbenchmark-dev
  gnuplot-nox  # perf/run-all.sh plots error against time
  libopenmpi-dev openmpi-bin  # rendering across machines (mpirun); a build without it renders on one
  libglfw3-dev libgl-dev  # lantern view's window (src/app/viewer.cpp)
  xvfb xauth xdotool libgl1-mesa-dri  # its test: a virtual display, keys sent to the window, OpenGL in software
  pybind11-dev python3-dev  # the Python module (docs/python.md)
  python3-numpy python3-pytest python3-matplotlib  # its arrays, its tests, the example study's plots
)
# scripts/check-sanitized.sh: sanitizers and libFuzzer. Not on a CI machine
# (LANTERN_CI=1, set by .ci/run), which does not run that suite.
[ "${LANTERN_CI:-}" = 1 ] || packages+=(clang libclang-rt-14-dev)

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done

if [ ${#missing[@]} -eq 0 ]; then
  exit 0
fi

SUDO=""
[ "$(id -u)" -eq 0 ] || SUDO="sudo"
echo "installing: ${missing[*]}" >&2
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
# On a CI machine (LANTERN_CI=1, set by .ci/run), dpkg unpacks without
# syncing each file to disk: the install takes a fraction of the time, and
# a machine that loses power mid-install is thrown away anyway.
unsafe=()
[ "${LANTERN_CI:-}" = 1 ] && unsafe=(-o Dpkg::Options::=--force-unsafe-io)
$SUDO apt-get install -y -qq --no-install-recommends "${unsafe[@]}" "${missing[@]}" >/dev/null
