#!/usr/bin/env bash
# `make install` works and FreeCAD then loads the add-on by itself, from its user Mod folder, with no
# path set by us: in a throw-away HOME, install, then in freecadcmd import the macro API, and in the
# GUI (offscreen) check that the "Remesh" workbench is registered. Exits non-zero on any failure.
set -euo pipefail
repo="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
home="$(mktemp -d)"
trap 'rm -rf "$home"' EXIT
export HOME="$home" XDG_DATA_HOME="$home/.local/share" XDG_CONFIG_HOME="$home/.config"
unset LIFTREMESH_MODULE_DIR PYTHONPATH

bash "$repo/scripts/install-addon.sh"   # what `make install` runs once the build is done
link="$(find "$home" -maxdepth 6 -name LiftRemesh -type l | head -n 1)"
[ -n "$link" ] || { echo "check_install: no LiftRemesh link under $home" >&2; exit 1; }
echo "check_install: installed at $link"

cat > "$home/check.py" <<'PY'
import os, sys, traceback
status = 1
try:
    import FreeCAD
    import LiftRemesh                      # found through Mod/LiftRemesh/package.xml -> freecad_workbench
    where = os.path.realpath(LiftRemesh.__file__)
    assert "/freecad_workbench/LiftRemesh/" in where, where
    assert LiftRemesh.defaults()["vertices"] > 0
    import FreeCADGui
    FreeCADGui.showMainWindow()
    names = FreeCADGui.listWorkbenches()
    assert "LiftRemeshWorkbench" in names, sorted(names)
    FreeCADGui.activateWorkbench("LiftRemeshWorkbench")
    assert "LiftRemesh_Remesh" in FreeCADGui.listCommands()
    print("check_install: LiftRemesh loaded from", where, "and the workbench is registered")
    status = 0
except BaseException:
    traceback.print_exc()
sys.stdout.flush()
os._exit(status)
PY
QT_QPA_PLATFORM=offscreen "${FREECADCMD:-freecadcmd}" "$home/check.py"
