# LiftRemesh add-on, GUI part: registers the "Remesh" workbench. FreeCAD execs this file at
# start-up without __file__ and with its own globals, so the workbench's methods import what they
# use and find the add-on through the package LiftRemesh beside this file (without importing it:
# registering the workbench must work even when the compiled module is missing).
import FreeCADGui


class LiftRemeshWorkbench(FreeCADGui.Workbench):
    """Remesh: Part shapes and meshes into well-shaped triangle meshes; FEM shell and solid meshes."""

    MenuText = "Remesh"
    ToolTip = "LiftRemesh: remesh Part shapes and meshes into well-shaped, feature-preserving triangle meshes"

    def __init__(self):
        import importlib.util
        import os

        spec = importlib.util.find_spec("LiftRemesh")
        if spec is not None and spec.submodule_search_locations:
            root = os.path.dirname(os.path.dirname(list(spec.submodule_search_locations)[0]))
            self.__class__.Icon = os.path.join(root, "resources", "icons", "LiftRemesh.svg")

    def Initialize(self):
        """Runs when the workbench is first activated: registers the commands, fills the
        toolbar and the menu. Without the compiled module the commands say why they cannot run."""
        import FreeCAD

        names = ["LiftRemesh_Remesh", "LiftRemesh_FemShell", "LiftRemesh_FemSolid"]
        try:
            from LiftRemesh.gui import commands

            names = list(commands.NAMES)
        except ImportError as error:
            message = str(error) if str(error).startswith("LiftRemesh") else "LiftRemesh: %s" % error
            self.register_unavailable(names, message, getattr(self, "Icon", ""))
            FreeCAD.Console.PrintError(message + "\n")
        self.appendToolbar("Remesh", names)
        self.appendMenu("Remesh", names)

    @staticmethod
    def register_unavailable(names, message, icon):
        """Registers commands that only show `message` (why LiftRemesh cannot be loaded)."""
        import FreeCADGui

        class Unavailable:
            def __init__(self, name):
                self.name = name

            def GetResources(self):
                return {"Pixmap": icon, "MenuText": self.name.split("_", 1)[1],
                        "ToolTip": "LiftRemesh cannot run: " + message}

            def IsActive(self):
                return True

            def Activated(self):
                from PySide import QtGui

                QtGui.QMessageBox.critical(FreeCADGui.getMainWindow(), "LiftRemesh cannot run", message)

        for name in names:
            if name not in FreeCADGui.listCommands():
                FreeCADGui.addCommand(name, Unavailable(name))

    def ContextMenu(self, recipient):
        """The commands also in the 3D view's and the tree's context menus."""
        self.appendContextMenu("Remesh", ["LiftRemesh_Remesh", "LiftRemesh_FemShell", "LiftRemesh_FemSolid"])

    def Activated(self):
        pass

    def Deactivated(self):
        pass

    def GetClassName(self):
        return "Gui::PythonWorkbench"


FreeCADGui.addWorkbench(LiftRemeshWorkbench())
