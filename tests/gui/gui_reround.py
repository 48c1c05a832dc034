"""The "Existing round" part of the GUI macro (run by test_gui_reround.py with MESHROUND_GUI_STEPS=reround):
a mesh of OCCT's 5 mm fillet of a box's top front edge; the Change round radius command opens the task
panel in that mode; a real click on the round recognises it (found radius shown, its facets highlighted);
a click on the flat top face is refused in red (not_a_round); the preview at 8 mm; OK makes the Rounding
in change mode; editing it opens the panel in that mode again."""
import math

import FreeCAD
import FreeCADGui
from pivy import coin

from gui_support import click, press_task_button, screenshot, show_model, step

R0, R1 = 5.0, 8.0
SIZE = (60.0, 40.0, 30.0)
ON_ROUND = FreeCAD.Vector(30, R0 - R0 * math.cos(math.pi / 4), SIZE[2] - R0 + R0 * math.sin(math.pi / 4))
ON_TOP_FACE = FreeCAD.Vector(30, 20, SIZE[2])


def filleted_box_mesh():
    """The box with its top front edge (y = 0, z = 30) filleted by OCCT at R0, meshed ~3 elements across."""
    import MeshPart
    import Part
    solid = Part.makeBox(*SIZE)
    edge = next(e for e in solid.Edges if all(abs(v.Point.y) < 1e-7 and abs(v.Point.z - SIZE[2]) < 1e-7
                                              for v in e.Vertexes))
    return MeshPart.meshFromShape(Shape=solid.makeFillet(R0, [edge]), MaxLength=0.7 * R0)


def run():
    from MeshRound.taskpanels import existing_round
    from MeshRound.taskpanels.round_edges import active_panel
    FreeCADGui.activateWorkbench("MeshRoundWorkbench")
    doc = FreeCAD.newDocument("Reround")
    base = doc.addObject("Mesh::Feature", "FilletedBox")
    base.Mesh = filleted_box_mesh()
    doc.recompute()
    view = FreeCADGui.ActiveDocument.ActiveView
    show_model(view)
    FreeCADGui.Selection.addSelection(doc.Name, base.Name)
    FreeCADGui.runCommand("MeshRound_ChangeRadius")
    FreeCADGui.updateGui()
    panel = active_panel()
    form = panel.form
    step("opened", {"pick": form.pick_target.currentText(), "title": form.windowTitle(),
                    "status": form.status.text()})
    form.live_preview.setChecked(False)  # the preview is asked for below, once
    click(view, ON_ROUND)  # a real mouse click on the round
    step("picked", {"seeds": [list(s) for s in panel.seeds], "found": form.found.text(),
                    "status": form.status.text(), "status_style": form.status.styleSheet(),
                    "strip_facets": [s["strip_facets"] for s in panel.strips],
                    "highlighted_facets": highlighted_facets(panel),
                    "listed_facets": len(existing_round.strip_facets(panel.strips))})
    step("highlight_screenshot", screenshot("gui_reround_pick.png"))
    click(view, ON_TOP_FACE)
    step("flat_face", {"seeds": len(panel.seeds), "status": form.status.text(), "style": form.status.styleSheet()})
    panel.set_radius(R1)
    result = panel.preview_now()
    step("preview", {"found_radius": result.report["found_radius"], "status": form.status.text(),
                     "facets": len(result.triangles)})
    step("preview_screenshot", screenshot("gui_reround_preview.png"))
    press_task_button("ok")
    rounding = doc.getObject("Rounding")
    step("made", {"operation": rounding.Operation, "found": list(rounding.FoundRadius),
                  "icon": rounding.ViewObject.Proxy.getIcon(),
                  "radius": rounding.Radius.Value, "state": rounding.State, "panel_closed": active_panel() is None})
    FreeCADGui.ActiveDocument.setEdit(rounding.Name, 0)
    FreeCADGui.updateGui()
    panel = active_panel()
    step("edit", {"pick": panel.form.pick_target.currentText(), "found": panel.form.found.text()})
    press_task_button("cancel")


def highlighted_facets(panel):
    """The facets the panel's mark layer outlines: the closed 4-point loops of its first drawing."""
    node = panel.overlays()[0]._content.getChild(0)  # existing_round.strips_node
    for i in range(node.getNumChildren()):
        child = node.getChild(i)
        if isinstance(child, coin.SoLineSet):
            counts = child.numVertices.getValues()
            return sum(1 for n in counts if n == 4)
    return 0
