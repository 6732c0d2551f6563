"""Finds and imports the compiled module `liftremesh` (native/python, built by CMake).

Looked for, in order: wherever Python already finds it (an installed copy); the folder in the
environment variable LIFTREMESH_MODULE_DIR; the add-on's own build folder `<add-on>/build/python`
(where `make build` puts it). The module is compiled for one Python version: FreeCAD must run that
one (Debian's FreeCAD runs /usr/bin/python3; `make build` builds for it).
"""
import importlib
import os
import sys

ADDON_ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))

_module = None

# OpenMP threads that wait for work sleep rather than spin (native/cli/main.cpp says why: a core
# busy with other work, FreeCAD's own for one, would otherwise slow a run far down). libgomp reads
# the policy when it is loaded, so it is set before the module is imported; a user's choice stands.
if "OMP_WAIT_POLICY" not in os.environ and "GOMP_SPINCOUNT" not in os.environ:
    os.environ["OMP_WAIT_POLICY"] = "PASSIVE"


def module_dirs():
    """Folders searched for the compiled module, besides sys.path."""
    dirs = []
    if os.environ.get("LIFTREMESH_MODULE_DIR"):
        dirs.append(os.environ["LIFTREMESH_MODULE_DIR"])
    dirs.append(os.path.join(ADDON_ROOT, "build", "python"))
    return dirs


def load():
    """The `liftremesh` module; raises ImportError saying how to build it when it is missing."""
    global _module
    if _module is not None:
        return _module
    try:
        _module = importlib.import_module("liftremesh")
        return _module
    except ImportError:
        pass
    for folder in module_dirs():
        if os.path.isdir(folder) and folder not in sys.path:
            sys.path.append(folder)
    try:
        _module = importlib.import_module("liftremesh")
    except ImportError as error:
        version = "%d.%d" % sys.version_info[:2]
        raise ImportError(
            "LiftRemesh: the compiled module 'liftremesh' for Python %s was not found or does not load "
            "(%s). Build it with 'make build' in %s, for the Python FreeCAD runs "
            "(cmake -DPython_EXECUTABLE=...), or set LIFTREMESH_MODULE_DIR to its folder."
            % (version, error, ADDON_ROOT)) from error
    return _module
