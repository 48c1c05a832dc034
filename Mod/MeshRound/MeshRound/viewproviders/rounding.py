"""View provider proxies of the Rounding feature and its RoundingSurfaces child (GUI only).

The C++ view providers come from the object types: Mesh::FeaturePython gets MeshGui::ViewProviderPython
(a mesh face-set view) and Part::FeaturePython gets PartGui::ViewProviderPython; these proxies only add
the icon, the tree children and editing.  Class paths are stored in .FCStd files: keep them stable.
"""
import FreeCADGui

from ..resources import icon_path

EDIT_MODE_DEFAULT = 0  # FreeCAD's "default" edit mode: our task panel (1 = transform, etc. stay FreeCAD's)


class _StatelessViewProvider:
    """Common base: attach the proxy, keep no state in the file, show an icon."""
    icon_name = ""

    def __init__(self, vobj):
        vobj.Proxy = self

    def attach(self, vobj):
        self.ViewObject = vobj
        self.Object = vobj.Object

    def getIcon(self):
        return icon_path(self.icon_name)

    def __getstate__(self):
        return None

    def __setstate__(self, state):
        return None

    dumps, loads = __getstate__, __setstate__  # the names FreeCAD >= 0.21 looks for


class ViewProviderRounding(_StatelessViewProvider):
    """Claims Base (hidden while the Rounding exists) and the surfaces child; edits in the task panel."""
    icon_name = "MeshRound_RoundEdges.svg"

    def claimChildren(self):
        from ..objects.surfaces import surfaces_of
        base = self.Object.Base
        return ([base] if base else []) + surfaces_of(self.Object)

    def doubleClicked(self, vobj):
        FreeCADGui.ActiveDocument.setEdit(vobj.Object.Name, EDIT_MODE_DEFAULT)
        return True

    def setEdit(self, vobj, mode=EDIT_MODE_DEFAULT):
        if mode != EDIT_MODE_DEFAULT:
            return None  # let FreeCAD handle its other modes (e.g. transform)
        from ..taskpanels.round_edges import RoundEdgesPanel
        FreeCADGui.Control.showDialog(RoundEdgesPanel(vobj.Object.Base, feature=vobj.Object))
        return True

    def unsetEdit(self, vobj, mode=EDIT_MODE_DEFAULT):
        if mode != EDIT_MODE_DEFAULT:
            return None
        FreeCADGui.Control.closeDialog()
        return True

    def onDelete(self, vobj, subelements):
        """Deleting a Rounding shows its Base again and deletes its surfaces child."""
        from ..objects.surfaces import surfaces_of
        obj = vobj.Object
        for child in surfaces_of(obj):
            obj.Document.removeObject(child.Name)
        if obj.Base and obj.Base.ViewObject:
            obj.Base.ViewObject.Visibility = True
        return True


class ViewProviderRoundingSurfaces(_StatelessViewProvider):
    icon_name = "MeshRound_Surfaces.svg"

