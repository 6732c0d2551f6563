#!/usr/bin/env bash
# Links this repository into FreeCAD's user Mod folder as Mod/LiftRemesh, as the Addon Manager
# would install it (package.xml at the top, the workbench in freecad_workbench/). FreeCAD then
# finds the compiled module in build/python (make build).
#
#   scripts/install-addon.sh [--uninstall]
#
# The Mod folder is asked from FreeCAD itself (FreeCAD.getUserAppDataDir(): ~/.local/share/FreeCAD/
# for 0.20 and 1.0, a versioned folder for later ones), through $FREECADCMD (default: freecadcmd);
# FREECAD_MOD_DIR=... overrides it. An existing link is replaced; a real folder is left alone.
set -euo pipefail

repo="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
freecadcmd="${FREECADCMD:-freecadcmd}"

mod_dir="${FREECAD_MOD_DIR:-}"
if [ -z "$mod_dir" ]; then
  command -v "$freecadcmd" >/dev/null || { echo "install-addon: $freecadcmd not found (set FREECADCMD or FREECAD_MOD_DIR)" >&2; exit 1; }
  # freecadcmd prints a banner: the answer is the line after the marker.
  data_dir="$("$freecadcmd" -c "import FreeCAD; print('LIFTREMESH_DATA_DIR=' + FreeCAD.getUserAppDataDir())" 2>/dev/null \
              | sed -n 's/^LIFTREMESH_DATA_DIR=//p' | tail -n 1)"
  [ -n "$data_dir" ] || { echo "install-addon: could not ask $freecadcmd for its user data folder" >&2; exit 1; }
  mod_dir="${data_dir%/}/Mod"
fi
target="$mod_dir/LiftRemesh"

if [ "${1:-}" = "--uninstall" ]; then
  if [ -L "$target" ]; then rm "$target"; echo "install-addon: removed $target"; else echo "install-addon: no link at $target"; fi
  exit 0
fi

if [ -e "$target" ] && [ ! -L "$target" ]; then
  echo "install-addon: $target exists and is not a link; remove it first (an Addon Manager copy?)" >&2
  exit 1
fi
mkdir -p "$mod_dir"
ln -sfn "$repo" "$target"
echo "install-addon: $target -> $repo"
if ! ls "$repo"/build/python/liftremesh*.so >/dev/null 2>&1; then
  echo "install-addon: note: the compiled module is not built yet: run 'make build'" >&2
fi
