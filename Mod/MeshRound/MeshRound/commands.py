"""GUI commands of the MeshRound workbench: name -> command object in COMMANDS (registered with FreeCAD
by MeshRoundGui.py, whose module name recorded macros import)."""
import os

import FreeCAD
import FreeCADGui

from .resources import icon_path

class RoundEdgesCommand:
    """Round sharp edges: opens the task panel on the selected (or only) mesh feature.

    If the selection carries a picked point on that mesh, it becomes the first seed.
    """

    EXISTING_ROUND = False  # the panel's pick mode: sharp edges
    RESOURCES = {
        "Pixmap": icon_path("MeshRound_RoundEdges.svg"),
        "MenuText": "Round sharp edges",
        "ToolTip": "Round sharp edge chains of a mesh with a rolling ball: pick next to an edge, "
                   "set the radius, preview, OK.",
    }

    def GetResources(self):
        return dict(self.RESOURCES)

    def IsActive(self):
        doc = FreeCAD.ActiveDocument
        return bool(doc) and not FreeCADGui.Control.activeDialog() and any(_is_mesh(o) for o in doc.Objects)

    def Activated(self):
        base, seeds = _base_and_seeds()
        if base is None:
            FreeCAD.Console.PrintError(f"MeshRound: select the mesh (or keep only one mesh visible) and run "
                                       f"{self.RESOURCES['MenuText']} again.\n")
            return
        from .objects.rounding import CHANGE_RADIUS, ROUND
        from .taskpanels.round_edges import RoundEdgesPanel
        operation = CHANGE_RADIUS if self.EXISTING_ROUND else ROUND
        FreeCADGui.Control.showDialog(RoundEdgesPanel(base, seeds=seeds, operation=operation))


class ChangeRadiusCommand(RoundEdgesCommand):
    """Change round radius: the same task panel in its "Existing round" pick mode (a click on an existing
    round recognises it and shows its radius; OK makes a Rounding that changes it)."""

    EXISTING_ROUND = True
    RESOURCES = {
        "Pixmap": icon_path("MeshRound_ChangeRadius.svg"),
        "MenuText": "Change round radius",
        "ToolTip": "Change the radius of an existing round of a mesh (a CAD fillet, a mesher's or MeshRound's): "
                   "click on the round, see the radius found, set the new one (0: sharp), preview, OK.",
    }


def _is_mesh(obj):
    return obj.isDerivedFrom("Mesh::Feature")


def _base_and_seeds():
    """The mesh feature to round and the points picked on it: the selection, else the only visible mesh."""
    for selection in FreeCADGui.Selection.getSelectionEx():
        if _is_mesh(selection.Object):
            return selection.Object, list(selection.PickedPoints)
    visible = [o for o in FreeCAD.ActiveDocument.Objects if _is_mesh(o) and o.ViewObject.Visibility]
    return (visible[0], []) if len(visible) == 1 else (None, [])


class ExportDeckCommand:
    """Export the selected Rounding, built on a Deck, as the rounded deck in the deck's own format."""

    def GetResources(self):
        return {
            "Pixmap": icon_path("MeshRound_Deck.svg"),
            "MenuText": "Export rounded deck",
            "ToolTip": "Write the selected Rounding (on a solver deck opened with File > Open) as the deck, "
                       "rounded: every other line, ID, part and set kept, in the deck's own format.",
        }

    def IsActive(self):
        from .deck_export import _is_rounding
        return any(_is_rounding(s.Object) for s in FreeCADGui.Selection.getSelectionEx())

    def Activated(self):
        from PySide import QtGui

        from .deck_export import _is_rounding, deck_chain, export_deck
        from .deck_formats import DECK_EXTENSIONS, deck_family
        from .errors import RoundingError
        rounding = next(s.Object for s in FreeCADGui.Selection.getSelectionEx() if _is_rounding(s.Object))
        try:
            deck, _ = deck_chain(rounding)
            family = deck_family(deck.File)
            stem, ext = os.path.splitext(deck.File)
            patterns = " ".join("*" + e for e, f in DECK_EXTENSIONS.items() if f == family)
            path, _ = QtGui.QFileDialog.getSaveFileName(
                FreeCADGui.getMainWindow(), "Export rounded deck", f"{stem}_{rounding.Name}{ext}",
                f"{family} deck ({patterns})")
            if not path:
                return
            result = export_deck(rounding, path)
        except RoundingError as exc:
            FreeCAD.Console.PrintError(f"MeshRound: export of {rounding.Label} refused: {exc}\n")
            QtGui.QMessageBox.warning(FreeCADGui.getMainWindow(), "Export rounded deck", str(exc))
            return
        FreeCAD.Console.PrintMessage(f"MeshRound: {rounding.Label} exported to {', '.join(result.paths)}\n")


# name -> command, in toolbar and menu order
COMMANDS = {"MeshRound_RoundEdges": RoundEdgesCommand(), "MeshRound_ChangeRadius": ChangeRadiusCommand(),
            "MeshRound_ExportDeck": ExportDeckCommand()}
