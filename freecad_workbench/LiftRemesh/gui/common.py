"""What the GUI modules share: where the add-on's icons and .ui files are, the selected objects,
and how a failure is reported (console, then a message box)."""
import os

import FreeCAD
import FreeCADGui
from PySide import QtGui

from .. import native

TITLE = "LiftRemesh"


def resource_path(*parts):
    """A file under the add-on's resources folder (icons/..., ui/...)."""
    return os.path.join(native.ADDON_ROOT, "resources", *parts)


def icon_path(name):
    """The path of one of the add-on's SVG icons, by file name."""
    return resource_path("icons", name)


def ui_path(name):
    """The path of one of the add-on's Qt Designer forms, by file name."""
    return resource_path("ui", name)


def active_document():
    """The active document (App), or None. In the GUI it follows the active 3D view."""
    return FreeCAD.ActiveDocument


def selected_objects():
    """The selected objects of the active document, in selection order."""
    doc = active_document()
    if doc is None:
        return []
    return list(FreeCADGui.Selection.getSelection(doc.Name))


def widget_alive(widget):
    """False when `widget` (any Qt object) is None or its C++ object is gone (a closed task
    panel's form and its children): touching it would raise RuntimeError."""
    if widget is None:
        return False
    try:
        import shiboken2 as shiboken
    except ImportError:
        try:
            import shiboken6 as shiboken
        except ImportError:
            return True
    return shiboken.isValid(widget)


def main_window():
    """The parent for message boxes (None when there is no main window)."""
    try:
        return FreeCADGui.getMainWindow()
    except Exception:  # no GUI main window
        return None


STATUS_MS = 10000  # how long a confirmation stays in the status bar


def show_status(message):
    """A confirmation the user sees without the report view: the main window's status bar, for
    STATUS_MS (FEM's Gmsh panel says its result in the panel; a command without a panel here)."""
    window = main_window()
    if window is not None:
        window.statusBar().showMessage(message, STATUS_MS)


def report_error(message, title=TITLE + ": error"):
    """A failure the user must see: in the report view (console) and in a message box."""
    FreeCAD.Console.PrintError("%s: %s\n" % (TITLE, message))
    QtGui.QMessageBox.critical(main_window(), title, str(message))


def report_warning(message, title=TITLE):
    """Something the user asked for did not happen (e.g. cancelled): console and message box."""
    FreeCAD.Console.PrintWarning("%s: %s\n" % (TITLE, message))
    QtGui.QMessageBox.warning(main_window(), title, str(message))


def describe_error(error):
    """A one-line description of an exception for the user."""
    details = error.args[0] if error.args else None
    if isinstance(details, dict) and details.get("sErrMsg"):  # FreeCAD's own exceptions
        text = str(details["sErrMsg"]).strip()
    else:
        text = str(error).strip()
    kind = type(error).__name__
    if not text:
        return kind
    if isinstance(error, (ValueError, ImportError)):
        return text  # their messages already say what was wrong
    return "%s (%s)" % (text, kind)
