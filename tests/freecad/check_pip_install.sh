#!/usr/bin/env bash
# The module installed with pip serves FreeCAD with no build tree anywhere: pip builds a wheel of a
# copy of this checkout without build/ (scikit-build-core, pyproject.toml); a venv with the system's
# packages installs it and remeshes with it; then, in a throw-away HOME, that pip installs the wheel
# where FreeCAD 1.x looks for add-ons' Python packages (<user data>/AdditionalPythonPackages/pyXY,
# where the Addon Manager puts them; FreeCAD ignores PYTHONPATH), the copy is linked into the Mod
# folder by install-addon.sh (`make install`), and freecadcmd imports LiftRemesh and remeshes a
# Part shape.
# Needs python3-scikit-build-core (Debian 13; scripts/test-freecad1.sh runs it there).
set -euo pipefail
repo="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
python="${PYTHON:-/usr/bin/python3}"
freecadcmd="${FREECADCMD:-freecadcmd}"
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT
say() { echo "check_pip_install: $*"; }

"$python" -c "import scikit_build_core" 2>/dev/null \
  || { echo "check_pip_install: scikit-build-core is not installed for $python" >&2; exit 1; }

# A clone's files, without build/ or out/: nothing compiled comes along.
mkdir -p "$tmp/src"
(cd "$repo" && tar --exclude=./build --exclude=./out --exclude=./.git -cf - .) | tar -xf - -C "$tmp/src"

say "pip wheel (scikit-build-core $("$python" -c 'import scikit_build_core; print(scikit_build_core.__version__)'))"
"$python" -m pip wheel --no-build-isolation --no-deps --no-index -w "$tmp/wheels" "$tmp/src" > "$tmp/wheel.log" 2>&1 \
  || { tail -n 40 "$tmp/wheel.log" >&2; echo "check_pip_install: pip wheel failed" >&2; exit 1; }
wheel="$(ls "$tmp"/wheels/liftremesh-*.whl)"
say "built $(basename "$wheel")"

"$python" -m venv --system-site-packages "$tmp/venv"
"$tmp/venv/bin/python" -m pip install --no-index --no-deps --quiet "$wheel"
"$tmp/venv/bin/python" "$repo/tests/python/check_wheel.py" --not-under "$tmp/src"
[ ! -e "$tmp/src/build" ] || { echo "check_pip_install: pip left a build/ in the source" >&2; exit 1; }

home="$tmp/home"
export HOME="$home" XDG_DATA_HOME="$home/.local/share" XDG_CONFIG_HOME="$home/.config"
unset LIFTREMESH_MODULE_DIR
# The add-on as `make install` puts it in FreeCAD's user Mod folder (a link to the build-free copy).
FREECADCMD="$freecadcmd" bash "$tmp/src/scripts/install-addon.sh" 2>/dev/null
link="$(find "$home" -maxdepth 6 -name LiftRemesh -type l | head -n 1)"
[ -n "$link" ] || { echo "check_pip_install: install-addon.sh made no Mod/LiftRemesh link" >&2; exit 1; }
data_dir="$(dirname "$(dirname "$link")")"
site="$data_dir/AdditionalPythonPackages/$("$python" -c 'import sys; print("py%d%d" % sys.version_info[:2])')"
"$tmp/venv/bin/python" -m pip install --no-index --no-deps --quiet --target "$site" "$wheel"

cat > "$tmp/use.py" <<'PY'
import os, sys, traceback
status = 1
try:
    import FreeCAD
    import Part
    import LiftRemesh
    import liftremesh
    site = os.environ["LIFTREMESH_EXPECTED_SITE"]
    where = os.path.realpath(liftremesh.__file__)
    assert where.startswith(os.path.realpath(site)), "liftremesh from %s, not the wheel's %s" % (where, site)
    assert not any(os.path.isdir(os.path.join(p, "build", "python")) for p in sys.path if p), "a build tree is on sys.path"
    shape = Part.makeBox(20, 12, 6).cut(Part.makeCylinder(3, 6, FreeCAD.Vector(10, 6, 0)))
    mesh = LiftRemesh.remesh_shape(shape, vertices=1500, seed=1)
    assert mesh.CountPoints == 1500, mesh.CountPoints
    assert mesh.isSolid() and not mesh.hasNonManifolds(), "not a closed manifold"
    chi = mesh.CountPoints - mesh.CountEdges + mesh.CountFacets
    assert chi == 0, chi   # a box with a through-hole: genus 1
    print("check_pip_install: FreeCAD %s remeshed a Part shape with liftremesh %s from %s: %d points, %d facets, chi %d"
          % (".".join(FreeCAD.Version()[:3]), liftremesh.__version__, where, mesh.CountPoints, mesh.CountFacets, chi))
    status = 0
except BaseException:
    traceback.print_exc()
sys.stdout.flush()
os._exit(status)
PY
LIFTREMESH_EXPECTED_SITE="$site" QT_QPA_PLATFORM=offscreen "$freecadcmd" "$tmp/use.py"
