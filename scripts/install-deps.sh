#!/usr/bin/env bash
# Installs the Debian packages LiftRemesh needs to build, test, run the demo and the benchmark.
# Idempotent: a machine that already has every package makes no apt call at all.
# Runs as root (CI) or through sudo when it is there.
set -euo pipefail

packages=(
  build-essential   # g++, make
  cmake
  libeigen3-dev     # linear algebra (core)
  libnanoflann-dev  # kd-tree neighbour search (core)
  liblbfgs-dev      # L-BFGS optimizer (core)
  libgtest-dev      # C++ tests
  pybind11-dev      # Python module (native/python)
  python3-numpy     # Python module, scripts
  python3-scipy     # FreeCAD tests: kd-trees for the exact Hausdorff distance (tests/freecad/mesh_checks.py)
  freecad-python3   # FreeCAD 0.20 with Part/MeshPart (OpenCASCADE): demo part, workbench
  time              # /usr/bin/time -v for peak memory in `make bench`
  calculix-ccx      # CalculiX solver: the FEM hand-off test runs a static shell analysis
  tetgen            # TetGen: tests fill remeshed surfaces with tetrahedra (tests/native/tetgen_test.cpp)
)

installed() {
  # dpkg-query prints "install ok installed" for an installed package; fails for an unknown one.
  [ "$(dpkg-query -W -f='${Status}' "$1" 2>/dev/null || true)" = "install ok installed" ]
}

missing=()
for p in "${packages[@]}"; do
  installed "$p" || missing+=("$p")
done

if [ ${#missing[@]} -eq 0 ]; then
  echo "install-deps: all ${#packages[@]} packages present"
  exit 0
fi

if [ "$(id -u)" -eq 0 ]; then
  as_root=()
elif command -v sudo >/dev/null 2>&1; then
  as_root=(sudo)
else
  echo "install-deps: missing ${missing[*]}; run as root or install sudo" >&2
  exit 1
fi

echo "install-deps: installing ${missing[*]}"
apt_get() { "${as_root[@]}" env DEBIAN_FRONTEND=noninteractive apt-get -q "$@" </dev/null; }
updated=0
# The package lists are empty on a fresh image: update once when apt cannot see the packages.
if [ -z "$(find /var/lib/apt/lists -maxdepth 1 -name '*_Packages*' -print -quit 2>/dev/null)" ] \
   || ! apt-cache show "${missing[@]}" >/dev/null 2>&1; then
  apt_get update
  updated=1
fi
# A stale list can name versions the mirror no longer has: update once and try again.
if ! apt_get install -y --no-install-recommends "${missing[@]}"; then
  [ "$updated" -eq 0 ] || exit 1
  apt_get update
  apt_get install -y --no-install-recommends "${missing[@]}"
fi
echo "install-deps: done"
