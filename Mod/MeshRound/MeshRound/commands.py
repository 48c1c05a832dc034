"""GUI commands of the MeshRound workbench: name -> command object in COMMANDS (registered with FreeCAD
by MeshRoundGui.py, whose module name recorded macros import)."""
import FreeCAD
import FreeCADGui

from .resources import icon_path

class RoundEdgesCommand:
    """Round sharp edges: opens the task panel on the selected (or only) mesh feature.

    If the selection carries a picked point on that mesh, it becomes the first seed.
    """

    def GetResources(self):
        return {
            "Pixmap": icon_path("MeshRound_RoundEdges.svg"),
            "MenuText": "Round sharp edges",
            "ToolTip": "Round sharp edge chains of a mesh with a rolling ball: pick next to an edge, "
                       "set the radius, preview, OK.",
        }

    def IsActive(self):
        doc = FreeCAD.ActiveDocument
        return bool(doc) and not FreeCADGui.Control.activeDialog() and any(_is_mesh(o) for o in doc.Objects)

    def Activated(self):
        base, seeds = _base_and_seeds()
        if base is None:
            FreeCAD.Console.PrintError("MeshRound: select the mesh to round (or keep only one mesh "
                                       "visible) and run Round sharp edges again.\n")
            return
        from .taskpanels.round_edges import RoundEdgesPanel
        FreeCADGui.Control.showDialog(RoundEdgesPanel(base, seeds=seeds))


def _is_mesh(obj):
    return obj.isDerivedFrom("Mesh::Feature")


def _base_and_seeds():
    """The mesh feature to round and the points picked on it: the selection, else the only visible mesh."""
    for selection in FreeCADGui.Selection.getSelectionEx():
        if _is_mesh(selection.Object):
            return selection.Object, list(selection.PickedPoints)
    visible = [o for o in FreeCAD.ActiveDocument.Objects if _is_mesh(o) and o.ViewObject.Visibility]
    return (visible[0], []) if len(visible) == 1 else (None, [])


# name -> command, in toolbar and menu order
COMMANDS = {"MeshRound_RoundEdges": RoundEdgesCommand()}
