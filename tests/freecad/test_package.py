"""package.xml as FreeCAD reads it: the core's App.Metadata (0.20 and 1.x) and, where FreeCAD has
it (0.21 on), the Addon Manager's own pure-Python reader `addonmanager_metadata`, which the Addon
Manager of FreeCAD 1.0 uses to list and install the add-on."""
import os
import re
import sys
import unittest

import FreeCAD

from LiftRemesh import native

PACKAGE_XML = os.path.join(native.ADDON_ROOT, "package.xml")


def cmake_version():
    with open(os.path.join(native.ADDON_ROOT, "CMakeLists.txt"), encoding="utf-8") as f:
        return re.search(r"project\(LiftRemesh VERSION ([0-9.]+)", f.read()).group(1)


def addon_manager_reader():
    """addonmanager_metadata.MetadataReader, or None where this FreeCAD has no such module."""
    folder = os.path.join(FreeCAD.getResourceDir(), "Mod", "AddonManager")
    if os.path.isdir(folder) and folder not in sys.path:
        sys.path.append(folder)
    try:
        import addonmanager_metadata
    except ImportError:
        return None
    return addonmanager_metadata.MetadataReader


class PackageTest(unittest.TestCase):
    def test_core_metadata_reader(self):
        metadata = FreeCAD.Metadata(PACKAGE_XML)
        self.assertEqual(metadata.Name, "LiftRemesh")
        self.assertEqual(metadata.Version, cmake_version())
        self.assertEqual(metadata.FreeCADMin.split(".")[:2], ["0", "20"])
        [workbench] = metadata.Content["workbench"]
        self.assertEqual(workbench.Classname, "LiftRemeshWorkbench")
        self.assertTrue(os.path.isfile(os.path.join(native.ADDON_ROOT, workbench.Subdirectory, "InitGui.py")))

    def test_addon_manager_reader(self):
        reader = addon_manager_reader()
        if reader is None:
            self.skipTest("FreeCAD %s has no addonmanager_metadata (0.21 on)" % ".".join(FreeCAD.Version()[:2]))
        metadata = reader.from_file(PACKAGE_XML)
        self.assertEqual(metadata.name, "LiftRemesh")
        self.assertEqual(metadata.version.version_as_list[:3], [int(n) for n in cmake_version().split(".")])
        self.assertEqual(metadata.pythonmin.version_as_list[:3], [3, 8, 0])
        self.assertLessEqual(metadata.pythonmin.version_as_list[:2], list(sys.version_info[:2]))
        self.assertEqual(metadata.freecadmin.version_as_list[:3], [0, 20, 0])
        [workbench] = metadata.content["workbench"]
        self.assertEqual(workbench.classname, "LiftRemeshWorkbench")
        self.assertEqual(workbench.subdirectory, "freecad_workbench")
        icon = os.path.normpath(os.path.join(native.ADDON_ROOT, workbench.subdirectory, workbench.icon))
        self.assertTrue(os.path.isfile(icon), icon)
        self.assertEqual([lic.name for lic in metadata.license], ["LGPL-2.1-or-later"])


def imported_modules(path):
    """The modules a Python file imports, anywhere in it, as absolute names within LiftRemesh."""
    import ast

    with open(path, encoding="utf-8") as f:
        tree = ast.parse(f.read(), path)
    names = set()
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            names.update(alias.name for alias in node.names)
        elif isinstance(node, ast.ImportFrom):
            base = "LiftRemesh" if node.level else ""
            module = ".".join(part for part in (base, node.module or "") if part)
            names.add(module)
            names.update(module + "." + alias.name for alias in node.names)
    return names


class LayersTest(unittest.TestCase):
    def test_no_app_module_imports_the_gui(self):
        """The App modules (LiftRemesh/*.py) never import LiftRemesh.gui, not even inside a function:
        the GUI attaches the view provider through feature.set_view_provider_hook(). The package's
        __init__, the macro API's facade (FEM's ObjectsFem), brings the GUI half in when the GUI is
        up, so that the hook is set for a macro run before the workbench is activated."""
        package = os.path.join(native.ADDON_ROOT, "freecad_workbench", "LiftRemesh")
        for name in sorted(os.listdir(package)):
            if name.endswith(".py") and name != "__init__.py":
                gui = sorted(m for m in imported_modules(os.path.join(package, name))
                             if m == "LiftRemesh.gui" or m.startswith("LiftRemesh.gui.") or m == "FreeCADGui")
                self.assertEqual(gui, [], "%s imports %s" % (name, ", ".join(gui)))


if __name__ == "__main__":
    unittest.main()
