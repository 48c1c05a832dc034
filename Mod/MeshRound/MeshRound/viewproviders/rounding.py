"""View provider proxy of the Rounding feature (GUI only).

Mesh::FeaturePython gets its C++ view provider from its type (MeshGui::ViewProviderPython, a shaded mesh);
this proxy adds the icon, the tree children (Base, which make_rounding hides, and the RoundingSurfaces
Part feature) and editing in the task panel.  The class path is stored in .FCStd files: keep it stable.
"""
import FreeCAD
import FreeCADGui

from ..objects.rounding import CHANGE_RADIUS, ROUND
from ..resources import icon_path

EDIT_MODE_DEFAULT = 0  # FreeCAD's "default" edit mode: our task panel (1 = transform, etc. stay FreeCAD's)


class ViewProviderRounding:
    def __init__(self, vobj):
        vobj.Proxy = self

    def attach(self, vobj):
        self.ViewObject = vobj
        self.Object = vobj.Object

    def getIcon(self):
        """The Change round radius icon for a Rounding in that operation, else Round sharp edges'."""
        changes = getattr(getattr(self, "Object", None), "Operation", ROUND) == CHANGE_RADIUS
        return icon_path("MeshRound_ChangeRadius.svg" if changes else "MeshRound_RoundEdges.svg")

    def claimChildren(self):
        obj = self.Object
        return [child for child in (obj.Base, getattr(obj, "Surfaces", None)) if child]

    def doubleClicked(self, vobj):
        FreeCADGui.ActiveDocument.setEdit(vobj.Object.Name, EDIT_MODE_DEFAULT)
        return True

    def setEdit(self, vobj, mode=EDIT_MODE_DEFAULT):
        if mode != EDIT_MODE_DEFAULT:
            return None  # let FreeCAD handle its other modes (e.g. transform)
        base = vobj.Object.Base
        if base is None or not base.isDerivedFrom("Mesh::Feature"):
            FreeCAD.Console.PrintError(f"MeshRound: {vobj.Object.Label} has no mesh Base to edit against; "
                                       "set its Base property first.\n")
            return False
        from ..taskpanels.round_edges import RoundEdgesPanel
        FreeCADGui.Control.showDialog(RoundEdgesPanel(base, feature=vobj.Object))
        return True

    def unsetEdit(self, vobj, mode=EDIT_MODE_DEFAULT):
        if mode != EDIT_MODE_DEFAULT:
            return None
        FreeCADGui.Control.closeDialog()
        return True

    def onDelete(self, vobj, subelements):
        """Deleting a Rounding deletes its surfaces child too and shows its Base again."""
        obj = vobj.Object
        child = getattr(obj, "Surfaces", None)
        if child:
            obj.Surfaces = None
            obj.Document.removeObject(child.Name)
        if obj.Base and obj.Base.ViewObject:
            obj.Base.ViewObject.Visibility = True
        return True

    # No state of its own (the icon path is computed): nothing to store in the file.
    def __getstate__(self):
        return None

    def __setstate__(self, state):
        return None

    dumps, loads = __getstate__, __setstate__  # the names FreeCAD >= 0.21 looks for
