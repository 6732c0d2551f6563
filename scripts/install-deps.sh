#!/usr/bin/env bash
# Installs the Debian packages LiftRemesh needs to build, test, run the demo and the benchmark,
# on Debian 12 (FreeCAD 0.20.2) and Debian 13 (FreeCAD 1.0).
# Idempotent: a machine that already has every package makes no network call at all.
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
  tetgen            # TetGen: fills remeshed surfaces with tetrahedra (FEM solid mesh, fem_solid.py; tetgen_test.cpp)
  xvfb              # a virtual X server: one FreeCAD test drives the real GUI window (tests/freecad/gui_window.py)
  xauth             # xvfb-run needs it
  python3-pyside2.qttest  # QTest: that test sends its clicks and keys through it
)

# Installed where the distribution has them; the tests that need one say they skipped without it.
optional=(
  calculix-ccx               # CalculiX solver: the FEM hand-off test runs a static shell analysis
                             # (Debian 12 only: Debian 13 has no calculix-ccx)
  gmsh                       # FreeCAD FEM's own mesher: the FEM solid test compares with its mesh of the B-rep
  python3-gmsh               # make bench: Gmsh's t13 recipe timed beside each case (scripts/bench_gmsh.py)
  python3-scikit-build-core  # `pip install .` without build isolation (Debian 13 only)
  python3-pip                # the pip-installed module check (tests/freecad/check_pip_install.sh)
  python3-venv
  clang                      # make fuzz: libFuzzer targets (tests/fuzz) built with clang,
  libclang-rt-dev            # its runtime (libFuzzer, ASan, UBSan)
  libomp-dev                 # and its OpenMP
)

installed() {
  # dpkg-query prints "install ok installed" for an installed package; fails for an unknown one.
  [ "$(dpkg-query -W -f='${Status}' "$1" 2>/dev/null || true)" = "install ok installed" ]
}

available() {
  # A candidate version in apt's lists (read locally, no network).
  local candidate
  candidate=$(apt-cache policy "$1" 2>/dev/null | awk '/Candidate:/ {print $2}')
  [ -n "$candidate" ] && [ "$candidate" != "(none)" ]
}

have_lists() {
  [ -n "$(find /var/lib/apt/lists -maxdepth 1 -name '*_Packages*' -print -quit 2>/dev/null)" ]
}

missing=()
for p in "${packages[@]}" "${optional[@]}"; do
  installed "$p" || missing+=("$p")
done

# Leaves out of `missing` the optional packages apt's lists do not have, naming them in `absent`.
# Only with lists read (an empty list would say every package is absent).
absent=()
drop_absent_optional() {
  local keep=() p
  for p in "${missing[@]+"${missing[@]}"}"; do
    if [[ " ${optional[*]} " == *" $p "* ]] && ! available "$p"; then absent+=("$p"); else keep+=("$p"); fi
  done
  missing=("${keep[@]+"${keep[@]}"}")
}
! have_lists || drop_absent_optional
not_here=""
[ ${#absent[@]} -eq 0 ] || not_here=" (not in this distribution: ${absent[*]})"

if [ ${#missing[@]} -eq 0 ]; then
  echo "install-deps: all packages present$not_here"
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
# Another install (a second checkout's build, unattended upgrades) may hold dpkg's lock: wait for it.
apt_get() {
  "${as_root[@]}" env DEBIAN_FRONTEND=noninteractive apt-get -q -o DPkg::Lock::Timeout=900 "$@" </dev/null
}
updated=0
# The package lists are empty on a fresh image: update once when apt cannot see the packages.
if ! have_lists || ! apt-cache show "${missing[@]}" >/dev/null 2>&1; then
  apt_get update
  updated=1
  # Now that the lists are read, leave out the optional packages this distribution lacks.
  drop_absent_optional
  [ ${#absent[@]} -eq 0 ] || echo "install-deps: not in this distribution: ${absent[*]}"
  [ ${#missing[@]} -gt 0 ] || { echo "install-deps: done"; exit 0; }
fi
# A stale list can name versions the mirror no longer has: update once and try again.
if ! apt_get install -y --no-install-recommends "${missing[@]}"; then
  [ "$updated" -eq 0 ] || exit 1
  apt_get update
  apt_get install -y --no-install-recommends "${missing[@]}"
fi
echo "install-deps: done"
