# Runs LiftRemesh's FreeCAD tests (unittest modules tests/freecad/test_*.py) inside freecadcmd:
#
#   LIFTREMESH_TESTS=test_module freecadcmd tests/freecad/run_tests.py
#
# Environment: LIFTREMESH_TESTS, comma-separated module names (default: every test_*.py here);
# LIFTREMESH_SOURCE_DIR, the repository (default: two levels above this file); LIFTREMESH_MODULE_DIR,
# the folder with the compiled `liftremesh` module (default: <source>/build/python).
# `freecadcmd FILE.py` exits 0 even when FILE raises, so this script ends with an explicit
# os._exit(status): 0 only when every test passed.
import os
import sys
import traceback
import unittest


def quiet_notifications():
    """FreeCAD 1.0's notification area deadlocks on its own mutex offscreen when a popup's raise()
    makes Qt print a warning (FreeCAD issue #32773): the tests run with its popups off, as a user
    can set them. The key does not exist before 1.0 and is harmless there."""
    import FreeCAD

    FreeCAD.ParamGet("User parameter:BaseApp/Preferences/NotificationArea").SetBool(
        "NonIntrusiveNotificationsEnabled", False)


def main():
    import FreeCAD

    print("FreeCAD %s, Python %s" % (".".join(FreeCAD.Version()[:3]), sys.version.split()[0]))
    quiet_notifications()
    here = os.path.dirname(os.path.abspath(__file__)) if "__file__" in globals() else None
    source = os.environ.get("LIFTREMESH_SOURCE_DIR") or os.path.dirname(os.path.dirname(here))
    tests_dir = os.path.join(source, "tests", "freecad")
    module_dir = os.environ.get("LIFTREMESH_MODULE_DIR") or os.path.join(source, "build", "python")
    os.environ["LIFTREMESH_MODULE_DIR"] = module_dir
    for path in (tests_dir, os.path.join(source, "freecad_workbench"), module_dir):
        if path not in sys.path:
            sys.path.insert(0, path)
    names = [n for n in os.environ.get("LIFTREMESH_TESTS", "").split(",") if n]
    if not names:
        names = sorted(f[:-3] for f in os.listdir(tests_dir) if f.startswith("test_") and f.endswith(".py"))
    suite = unittest.defaultTestLoader.loadTestsFromNames(names)
    result = unittest.TextTestRunner(stream=sys.stdout, verbosity=2).run(suite)
    ran_something = result.testsRun > 0
    return 0 if result.wasSuccessful() and ran_something else 1


if __name__ in ("__main__", "run_tests") or True:
    try:
        status = main()
    except BaseException:  # an import error, a bad name: still a failure, never exit 0
        traceback.print_exc()
        status = 1
    sys.stdout.flush()
    sys.stderr.flush()
    os._exit(status)
