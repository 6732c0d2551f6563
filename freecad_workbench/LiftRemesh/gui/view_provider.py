"""View provider of the remesh feature: its icon, triangles visible ("Flat Lines"), the source
hidden while the remeshed mesh exists, and a double click to edit it in the task panel."""
import FreeCAD
import FreeCADGui

from .. import feature
from . import common

DISPLAY_MODE = "Flat Lines"
EDIT_MODE_DEFAULT = 0


class ViewProviderRemesh(feature.StatelessProxy):
    """Proxy of the remesh feature's view object (Mesh::FeaturePython)."""

    def __init__(self, vobj):
        vobj.Proxy = self
        self.attach(vobj)
        if DISPLAY_MODE in vobj.listDisplayModes():
            vobj.DisplayMode = DISPLAY_MODE
        # Created inside the caller's transaction: undoing it shows the source again.
        set_source_visible(vobj.Object, False)

    def attach(self, vobj):
        self.ViewObject = vobj
        self.Object = vobj.Object

    def getIcon(self):
        return common.icon_path("LiftRemesh_Feature.svg")

    def getDefaultDisplayMode(self):
        return DISPLAY_MODE

    def onDelete(self, vobj, subelements):
        """Deleting the remeshed mesh shows its source again."""
        set_source_visible(vobj.Object, True)
        return True

    def doubleClicked(self, vobj):
        """Opens the task panel to edit the parameters (and remesh again)."""
        if FreeCADGui.Control.activeDialog():
            return False
        return bool(vobj.Document.setEdit(vobj.Object.Name, EDIT_MODE_DEFAULT))

    def setEdit(self, vobj, mode=0):
        if mode != EDIT_MODE_DEFAULT:
            return None  # other edit modes (e.g. Transform) as FreeCAD does them
        from . import task_panel

        obj = vobj.Object
        try:
            if obj.Source is None:
                raise ValueError("it has no source to remesh")
            panel = task_panel.RemeshTaskPanel([obj.Source], feature=obj)
        except Exception as error:
            common.report_error("%s cannot be edited: %s" % (obj.Label, common.describe_error(error)))
            return False
        FreeCADGui.Control.showDialog(panel)
        return True

    def unsetEdit(self, vobj, mode=0):
        if mode != EDIT_MODE_DEFAULT:
            return None
        FreeCADGui.Control.closeDialog()
        return True


def set_source_visible(obj, visible):
    """Shows or hides a remesh feature's source, when it has one that still exists."""
    source = getattr(obj, "Source", None)
    if source is None or getattr(source, "ViewObject", None) is None:
        return
    try:
        if visible:
            source.ViewObject.show()
        else:
            source.ViewObject.hide()
    except Exception as error:  # a source being deleted: nothing to show
        FreeCAD.Console.PrintLog("LiftRemesh: cannot change the visibility of the source: %s\n" % error)
